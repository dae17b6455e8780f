#include "wbi/estimation/derivative_estimator.hpp"

#include <stdexcept>
#include <string>

namespace wbi::estimation {

DerivativeEstimator::DerivativeEstimator(Eigen::Index joints, const StreamParameters& stream)
    : stamps_(stream.sample_rate_hz, stream.max_gap_s) {
  if (joints <= 0) {
    throw std::invalid_argument("an estimator needs at least one joint, got " +
                                std::to_string(joints));
  }
  dq_ = Eigen::VectorXd::Zero(joints);
  ddq_ = Eigen::VectorXd::Zero(joints);
}

SampleStatus DerivativeEstimator::update(std::int64_t stamp_ns,
                                         const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (q.size() != joints()) {
    throw std::invalid_argument("estimator update: q has " + std::to_string(q.size()) +
                                " values, expected " + std::to_string(joints()));
  }
  if (!q.allFinite()) {
    stamps_.count_non_finite();
    return SampleStatus::non_finite;
  }
  double dt_s = 0.0;
  const SampleStatus status = stamps_.check(stamp_ns, dt_s);
  switch (status) {
    case SampleStatus::first:
    case SampleStatus::after_gap:
      dq_.setZero();
      ddq_.setZero();
      start(q);
      break;
    case SampleStatus::accepted:
      step(dt_s, q, dq_, ddq_);
      break;
    default:
      break;  // ignored: estimates held
  }
  return status;
}

void DerivativeEstimator::reset() {
  stamps_.reset();
  dq_.setZero();
  ddq_.setZero();
}

}  // namespace wbi::estimation
