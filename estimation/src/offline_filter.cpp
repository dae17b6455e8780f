#include "wbi/estimation/offline_filter.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wbi::estimation {

std::int64_t stamp_from_seconds(double t_s) { return std::llround(t_s * 1e9); }

JointDerivatives estimate_offline(DerivativeEstimator& estimator, const JointSamples& samples) {
  const Eigen::Index joints = samples.q.cols();
  if (estimator.joints() != joints) {
    throw std::invalid_argument("estimator built for " + std::to_string(estimator.joints()) +
                                " joints, the trajectory has " + std::to_string(joints));
  }
  const auto rows = static_cast<Eigen::Index>(samples.t.size());
  JointDerivatives out;
  out.t = samples.t;
  out.dq.resize(rows, joints);
  out.ddq.resize(rows, joints);
  estimator.reset();
  Eigen::VectorXd q(joints);
  for (Eigen::Index r = 0; r < rows; ++r) {
    q = samples.q.row(r).transpose();
    estimator.update(stamp_from_seconds(samples.t[static_cast<std::size_t>(r)]), q);
    out.dq.row(r) = estimator.velocity().transpose();
    out.ddq.row(r) = estimator.acceleration().transpose();
  }
  return out;
}

}  // namespace wbi::estimation
