#include "wbi/estimation/split_kalman.hpp"

#include "wbi/estimation/low_pass_filter.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wbi::estimation {
namespace {

std::vector<JointKalmanFilters> acceleration_bank(Eigen::Index joints,
                                                  const SplitKalmanParameters& p, double period_s) {
  if (p.acceleration_models < 1 || p.acceleration_models > 8) {
    throw std::invalid_argument("split-kalman: acceleration-models must be in [1, 8], got " +
                                std::to_string(p.acceleration_models));
  }
  if (!(p.acceleration_noise_max >= p.acceleration_noise_min)) {
    throw std::invalid_argument(
        "split-kalman: acceleration-noise-max must be >= acceleration-noise-min, got " +
        std::to_string(p.acceleration_noise_max) + " < " +
        std::to_string(p.acceleration_noise_min));
  }
  if (!(p.velocity_cutoff_hz >= 0.0) || !std::isfinite(p.velocity_cutoff_hz)) {
    throw std::invalid_argument("split-kalman: velocity-cutoff must be >= 0 Hz, got " +
                                std::to_string(p.velocity_cutoff_hz));
  }
  if (!(p.acceleration_memory_s > 0.0) || !std::isfinite(p.acceleration_memory_s)) {
    throw std::invalid_argument("split-kalman: acceleration-memory must be > 0 s, got " +
                                std::to_string(p.acceleration_memory_s));
  }
  std::vector<JointKalmanFilters> bank;
  bank.reserve(static_cast<std::size_t>(p.acceleration_models));
  const double ratio = p.acceleration_noise_max / p.acceleration_noise_min;
  for (int i = 0; i < p.acceleration_models; ++i) {
    // Geometric spacing from the minimum to the maximum.
    const double u =
        p.acceleration_models > 1 ? static_cast<double>(i) / (p.acceleration_models - 1) : 0.0;
    bank.emplace_back("split-kalman (acceleration)", joints, p.acceleration_order,
                      p.resolution_counts, p.acceleration_noise_min * std::pow(ratio, u), period_s);
  }
  return bank;
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
      acceleration_filters_(acceleration_bank(joints, params, 1.0 / stream.sample_rate_hz)),
      memory_s_(params.acceleration_memory_s),
      log_likelihood_(Eigen::MatrixXd::Zero(params.acceleration_models, joints)),
      weights_(Eigen::MatrixXd::Constant(params.acceleration_models, joints,
                                         1.0 / params.acceleration_models)) {}

void SplitKalmanEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  velocity_filters_.start(q);
  for (auto& filters : acceleration_filters_) {
    filters.start(q);
  }
  log_likelihood_.setZero();
  weights_.setConstant(1.0 / static_cast<double>(weights_.rows()));
}

void SplitKalmanEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                                Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  velocity_filters_.step(dt_s, q);
  velocity_filters_.velocity(velocity_);
  dq += low_pass_gain(velocity_cutoff_hz_, dt_s) * (velocity_ - dq);
  const double forget = std::exp(-dt_s / memory_s_);
  const auto models = static_cast<Eigen::Index>(acceleration_filters_.size());
  for (Eigen::Index i = 0; i < models; ++i) {
    auto& filters = acceleration_filters_[static_cast<std::size_t>(i)];
    filters.step(dt_s, q);
    const double S = filters.innovation_variance();
    const double log_S = std::log(S);
    for (Eigen::Index j = 0; j < joints(); ++j) {
      const double nu = filters.innovation()(j);
      log_likelihood_(i, j) = forget * log_likelihood_(i, j) + nu * nu / S + log_S;
    }
  }
  for (Eigen::Index j = 0; j < joints(); ++j) {
    // Weights relative to the likeliest model, so that exp never underflows to 0/0.
    const double best = log_likelihood_.col(j).minCoeff();
    double total = 0.0;
    double blended = 0.0;
    for (Eigen::Index i = 0; i < models; ++i) {
      const double w = std::exp(-0.5 * (log_likelihood_(i, j) - best));
      weights_(i, j) = w;
      total += w;
      blended += w * acceleration_filters_[static_cast<std::size_t>(i)].acceleration(j);
    }
    weights_.col(j) /= total;
    ddq(j) = blended / total;
  }
}

}  // namespace wbi::estimation
