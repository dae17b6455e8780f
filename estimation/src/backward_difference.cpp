#include "wbi/estimation/backward_difference.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "wbi/estimation/low_pass_filter.hpp"

namespace wbi::estimation {

BackwardDifferenceEstimator::BackwardDifferenceEstimator(Eigen::Index joints,
                                                         const BackwardDifferenceParameters& params,
                                                         const StreamParameters& stream)
    : DerivativeEstimator(joints, stream), params_(params) {
  if (!(params.cutoff_hz >= 0.0) || !std::isfinite(params.cutoff_hz)) {
    throw std::invalid_argument(
        "backward-difference: cutoff must be >= 0 Hz (0: no low-pass), got " +
        std::to_string(params.cutoff_hz));
  }
  q_previous_ = Eigen::VectorXd::Zero(joints);
}

void BackwardDifferenceEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  q_previous_ = q;
  dt_previous_ = 0.0;
}

void BackwardDifferenceEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                                       Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  const double gain = low_pass_gain(params_.cutoff_hz, dt_s);
  // The velocity difference is centred between the two intervals' midpoints.
  const double ddq_scale = dt_previous_ > 0.0 ? 2.0 / (dt_s + dt_previous_) : 0.0;
  for (Eigen::Index j = 0; j < joints(); ++j) {
    const double dq_new = dq(j) + gain * ((q(j) - q_previous_(j)) / dt_s - dq(j));
    // The first difference has no previous velocity: its acceleration stays zero.
    const double ddq_raw = (dq_new - dq(j)) * ddq_scale;
    ddq(j) = dt_previous_ > 0.0 ? ddq(j) + gain * (ddq_raw - ddq(j)) : 0.0;
    dq(j) = dq_new;
  }
  q_previous_ = q;
  dt_previous_ = dt_s;
}

}  // namespace wbi::estimation
