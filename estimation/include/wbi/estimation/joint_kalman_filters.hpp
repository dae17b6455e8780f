// One integrator-chain Kalman filter per joint (see integrator_chain.hpp), all
// sharing one model and one covariance: the Riccati step runs once per
// sample, a joint costs one small matrix-vector prediction and a rank-one
// correction. The building block of the `kalman` and `split-kalman` methods.
#pragma once

#include <Eigen/Core>

#include "wbi/estimation/integrator_chain.hpp"

namespace wbi::estimation {

class JointKalmanFilters {
 public:
  // See IntegratorChain for the parameters; `method` names errors.
  JointKalmanFilters(const char* method, Eigen::Index joints, int order, double counts,
                     double sigma_w, double period_s);

  // At rest at q with the steady-state covariance: no start-up transient.
  void start(const Eigen::Ref<const Eigen::VectorXd>& q);
  // The next sample, dt_s > 0 after the previous one. Never allocates.
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q);
  // The same sample as `stepped`, a filter set of the same model and joints
  // that has just run step(): its transition and gain are reused, so the
  // Riccati step runs once for both. Use either this or step(), never both,
  // on one object (the covariance is only advanced by step()).
  void step_like(const JointKalmanFilters& stepped, const Eigen::Ref<const Eigen::VectorXd>& q);
  // The current estimates in SI units (rad/s, rad/s²).
  void velocity(Eigen::VectorXd& dq) const { dq = x_.row(1).transpose() * to_velocity_; }
  void acceleration(Eigen::VectorXd& ddq) const {
    ddq = x_.row(2).transpose() * (to_velocity_ * to_velocity_);
  }
  double velocity(Eigen::Index j) const { return x_(1, j) * to_velocity_; }
  double acceleration(Eigen::Index j) const { return x_(2, j) * to_velocity_ * to_velocity_; }
  // Sets joint j's acceleration (rad/s²) and zeroes its higher derivatives:
  // a jump the filter is told about instead of finding it in the innovations.
  void set_acceleration(Eigen::Index j, double ddq);
  // Adds `delta` (rad/s²) to joint j's acceleration, its other states untouched:
  // a known input (a ramp) rather than a jump.
  void add_acceleration(Eigen::Index j, double delta);
  const IntegratorChain& model() const { return chain_; }
  // Of the last step: per joint the innovation q − q̂⁻ (rad), and its
  // predicted variance S = P⁻_00 + r (rad², the same for every joint).
  const Eigen::VectorXd& innovation() const { return innovation_; }
  double innovation_variance() const { return innovation_variance_; }

 private:
  // Predicts with F_ and corrects with K_ every joint; sets innovation_.
  void correct(const Eigen::Ref<const Eigen::VectorXd>& q);

  IntegratorChain chain_;
  IntegratorChain::States x_;  // (kStates × joints) scaled state per joint
  double to_velocity_;         // 1/T: scaled units to SI
  double measurement_variance_;
  Eigen::VectorXd innovation_;
  double innovation_variance_;
  IntegratorChain::Matrix F_;  // transition of the last step
  IntegratorChain::Vector K_;  // gain of the last step
};

}  // namespace wbi::estimation
