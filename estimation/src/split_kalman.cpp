#include "wbi/estimation/split_kalman.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "wbi/estimation/low_pass_filter.hpp"

namespace wbi::estimation {
namespace {

constexpr const char* kMethod = "split-kalman";

double sign(double x) { return static_cast<double>((x > 0.0) - (x < 0.0)); }

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
  require(p.stick_release_s >= 0.0 && std::isfinite(p.stick_release_s),
          "stick-release must be >= 0 s, got " + std::to_string(p.stick_release_s));
  require(p.stick_velocity >= 0.0 && std::isfinite(p.stick_velocity),
          "stick-velocity must be >= 0 rad/s, got " + std::to_string(p.stick_velocity));
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
      stick_release_s_(params.stick_release_s),
      stick_velocity_(params.stick_velocity),
      stick_memory_s_(params.stick_memory_s),
      stick_phase_(static_cast<std::size_t>(joints), StickPhase::kNone),
      stick_elapsed_s_(Eigen::VectorXd::Zero(joints)),
      stick_gap_(Eigen::VectorXd::Zero(joints)),
      reversal_sign_(Eigen::VectorXd::Zero(joints)),
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
  std::fill(stick_phase_.begin(), stick_phase_.end(), StickPhase::kNone);
  stick_elapsed_s_.setZero();
  stick_gap_.setZero();
  reversal_sign_.setZero();
  family_likelihood_.setZero();
  stick_weight_.setZero();
}

void SplitKalmanEstimator::anticipate_sticks(double dt_s) {
  for (Eigen::Index j = 0; j < joints(); ++j) {
    auto& phase = stick_phase_[static_cast<std::size_t>(j)];
    if (phase != StickPhase::kNone) {
      stick_elapsed_s_(j) += dt_s;
      release_stick(j);
    }
    if (phase == StickPhase::kNone) {
      start_stick_at_reversal(j);
    }
  }
}

// A joint reverses when it slows down within stick_velocity_ of zero (the
// friction then holds it before the sign change shows: waiting for the sign
// change comes a few samples late) or, failing that, when its velocity
// changes sign. Each reversal starts one stick: reversal_sign_ keeps the
// direction it reversed from.
void SplitKalmanEstimator::start_stick_at_reversal(Eigen::Index j) {
  const double v = moving_.velocity(j);
  const double before = previous_velocity_(j);
  const bool slowing_to_zero = v * moving_.acceleration(j) < 0.0 && std::abs(v) < stick_velocity_ &&
                               sign(v) != reversal_sign_(j);
  const bool crossed_zero = before * v < 0.0 && sign(before) != reversal_sign_(j);
  if (!slowing_to_zero && !crossed_zero) {
    return;
  }
  reversal_sign_(j) = slowing_to_zero ? sign(v) : sign(before);
  sticking_->stick(j, stick_fraction_);
  stick_phase_[static_cast<std::size_t>(j)] = StickPhase::kHolding;
  stick_elapsed_s_(j) = 0.0;
  stick_gap_(j) = 1.0;
}

// After stick_duration_s_ the acceleration returns to the value it had,
// the gap closing as exp(−t / stick_release_s_): the first step sets it (what
// the filters learnt meanwhile is dropped), the later ones add to it. After
// four time constants the rest of the gap closes at once.
void SplitKalmanEstimator::release_stick(Eigen::Index j) {
  const double tolerance_s = 0.5 / sample_rate_hz();
  const double released_s = stick_elapsed_s_(j) - stick_duration_s_;
  if (released_s < -tolerance_s) {
    return;  // still holding
  }
  const bool done = released_s + tolerance_s >= 4.0 * stick_release_s_;
  const double gap = done ? 0.0 : std::exp(-std::max(released_s, 0.0) / stick_release_s_);
  auto& phase = stick_phase_[static_cast<std::size_t>(j)];
  if (phase == StickPhase::kHolding) {
    sticking_->slip(j, 1.0 - (1.0 - stick_fraction_) * gap);
  } else {
    sticking_->recover(j, (1.0 - stick_fraction_) * (stick_gap_(j) - gap));
  }
  stick_gap_(j) = gap;
  phase = done ? StickPhase::kNone : StickPhase::kReleasing;
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
