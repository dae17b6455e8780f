// Kalman filter on the integrator-chain model of each joint (see
// integrator_chain.hpp): one model, one shared covariance that starts at its
// steady state for the nominal rate and follows the actual intervals, so
// dropped samples and jitter keep the filter optimal. Per joint a sample costs
// one small matrix-vector prediction and a rank-one correction.
#pragma once

#include "wbi/estimation/derivative_estimator.hpp"
#include "wbi/estimation/joint_kalman_filters.hpp"

namespace wbi::estimation {

struct KalmanParameters {
  int model_order = 3;  // 2: constant acceleration, 3: constant jerk, 4: constant snap
  double resolution_counts = 16384.0;  // encoder counts per revolution (2^14)
  double process_noise = 300.0;        // σ_w, rad/s^(order+1)/√Hz
};

class KalmanEstimator final : public DerivativeEstimator {
 public:
  KalmanEstimator(Eigen::Index joints, const KalmanParameters& params,
                  const StreamParameters& stream = {});
  const char* method() const override { return "kalman"; }
  const IntegratorChain& model() const { return filters_.model(); }

 private:
  void start(const Eigen::Ref<const Eigen::VectorXd>& q) override;
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
            Eigen::VectorXd& ddq) override;

  JointKalmanFilters filters_;
};

}  // namespace wbi::estimation
