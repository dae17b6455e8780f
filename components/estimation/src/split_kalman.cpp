#include "wbi/estimation/split_kalman.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "wbi/estimation/low_pass_filter.hpp"

namespace wbi::estimation {
namespace {

constexpr const char* kMethod = "split-kalman";

void require(bool ok, const std::string& message) {
  if (!ok) {
    throw std::invalid_argument(std::string(kMethod) + ": " + message);
  }
}

AccelerationBankParameters bank_parameters(const SplitKalmanParameters& p) {
  require(p.velocity_cutoff_hz >= 0.0 && std::isfinite(p.velocity_cutoff_hz),
          "velocity-cutoff must be >= 0 Hz, got " + std::to_string(p.velocity_cutoff_hz));
  require(p.acceleration_memory_s > 0.0 && std::isfinite(p.acceleration_memory_s),
          "acceleration-memory must be > 0 s, got " + std::to_string(p.acceleration_memory_s));
  require(p.stick_duration_s >= 0.0 && std::isfinite(p.stick_duration_s),
          "stick-duration must be >= 0 s, got " + std::to_string(p.stick_duration_s));
  require(p.stick_fraction >= 0.0 && p.stick_fraction <= 1.0,
          "stick-fraction must be in [0, 1], got " + std::to_string(p.stick_fraction));
  require(p.stick_memory_s > 0.0 && std::isfinite(p.stick_memory_s),
          "stick-memory must be > 0 s, got " + std::to_string(p.stick_memory_s));
  return {p.acceleration_order, p.resolution_counts, p.acceleration_noise_min,
          p.acceleration_noise_max, p.acceleration_models};
}

std::optional<AccelerationBank> sticking_bank(Eigen::Index joints, const SplitKalmanParameters& p,
                                              double period_s) {
  if (p.stick_duration_s <= 0.0) {
    return std::nullopt;
  }
  return AccelerationBank("split-kalman (acceleration)", joints, bank_parameters(p), period_s);
}

}  // namespace

SplitKalmanEstimator::SplitKalmanEstimator(Eigen::Index joints, const SplitKalmanParameters& params,
                                           const StreamParameters& stream)
    : DerivativeEstimator(joints, stream),
      velocity_filters_("split-kalman (velocity)", joints, params.velocity_order,
                        params.resolution_counts, params.velocity_process_noise,
                        1.0 / stream.sample_rate_hz),
      velocity_cutoff_hz_(params.velocity_cutoff_hz),
      velocity_(Eigen::VectorXd::Zero(joints)),
      previous_velocity_(Eigen::VectorXd::Zero(joints)),
      memory_s_(params.acceleration_memory_s),
      moving_("split-kalman (acceleration)", joints, bank_parameters(params),
              1.0 / stream.sample_rate_hz),
      sticking_(sticking_bank(joints, params, 1.0 / stream.sample_rate_hz)),
      stick_duration_s_(params.stick_duration_s),
      stick_fraction_(params.stick_fraction),
      stick_memory_s_(params.stick_memory_s),
      stick_remaining_s_(Eigen::VectorXd::Zero(joints)),
      family_likelihood_(Eigen::Matrix2Xd::Zero(2, joints)),
      stick_weight_(Eigen::VectorXd::Zero(joints)) {}

void SplitKalmanEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  velocity_filters_.start(q);
  velocity_.setZero();
  previous_velocity_.setZero();
  moving_.start(q);
  if (sticking_) {
    sticking_->start(q);
  }
  stick_remaining_s_.setZero();
  family_likelihood_.setZero();
  stick_weight_.setZero();
}

void SplitKalmanEstimator::anticipate_sticks(double dt_s) {
  const double tolerance_s = 0.5 / sample_rate_hz();
  for (Eigen::Index j = 0; j < joints(); ++j) {
    if (stick_remaining_s_(j) > 0.0) {
      stick_remaining_s_(j) -= dt_s;
      if (stick_remaining_s_(j) < tolerance_s) {
        sticking_->slip(j);
        stick_remaining_s_(j) = 0.0;
      }
    } else if (previous_velocity_(j) * moving_.velocity(j) < 0.0) {
      // A velocity reversal: assume the joint sticks from now on.
      sticking_->stick(j, stick_fraction_);
      stick_remaining_s_(j) = stick_duration_s_;
    }
  }
}

void SplitKalmanEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                                Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  velocity_filters_.step(dt_s, q);
  velocity_filters_.velocity(velocity_);
  dq += low_pass_gain(velocity_cutoff_hz_, dt_s) * (velocity_ - dq);
  for (Eigen::Index j = 0; j < joints(); ++j) {
    previous_velocity_(j) = moving_.velocity(j);
  }
  const double bank_forget = std::exp(-dt_s / memory_s_);
  moving_.step(dt_s, q, bank_forget);
  if (!sticking_) {
    for (Eigen::Index j = 0; j < joints(); ++j) {
      ddq(j) = moving_.acceleration(j);
    }
    return;
  }
  sticking_->step_like(moving_, q, bank_forget);
  anticipate_sticks(dt_s);
  const double forget = std::exp(-dt_s / stick_memory_s_);
  for (Eigen::Index j = 0; j < joints(); ++j) {
    family_likelihood_(0, j) = forget * family_likelihood_(0, j) + moving_.innovation_score(j);
    family_likelihood_(1, j) = forget * family_likelihood_(1, j) + sticking_->innovation_score(j);
    // w = 1 / (1 + exp((ℓ_stick − ℓ_moving) / 2)), bounded so that exp never overflows.
    const double d =
        std::clamp(0.5 * (family_likelihood_(1, j) - family_likelihood_(0, j)), -50.0, 50.0);
    stick_weight_(j) = 1.0 / (1.0 + std::exp(d));
    ddq(j) = (1.0 - stick_weight_(j)) * moving_.acceleration(j) +
             stick_weight_(j) * sticking_->acceleration(j);
  }
}

}  // namespace wbi::estimation
