#include "wbi/estimation/kalman_derivative.hpp"

namespace wbi::estimation {

KalmanEstimator::KalmanEstimator(Eigen::Index joints, const KalmanParameters& params,
                                 const StreamParameters& stream)
    : DerivativeEstimator(joints, stream),
      filters_("kalman", joints, params.model_order, params.resolution_counts, params.process_noise,
               1.0 / stream.sample_rate_hz) {}

void KalmanEstimator::start(const Eigen::Ref<const Eigen::VectorXd>& q) { filters_.start(q); }

void KalmanEstimator::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q,
                           Eigen::VectorXd& dq, Eigen::VectorXd& ddq) {
  filters_.step(dt_s, q);
  filters_.velocity(dq);
  filters_.acceleration(ddq);
}

}  // namespace wbi::estimation
