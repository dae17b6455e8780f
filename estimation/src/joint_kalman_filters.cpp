#include "wbi/estimation/joint_kalman_filters.hpp"

namespace wbi::estimation {

JointKalmanFilters::JointKalmanFilters(const char* method, Eigen::Index joints, int order,
                                       double counts, double sigma_w, double period_s)
    : chain_(method, order, counts, sigma_w, period_s),
      x_(IntegratorChain::States::Zero(IntegratorChain::kStates, joints)),
      to_velocity_(1.0 / period_s),
      measurement_variance_(IntegratorChain::quantisation_variance(counts)),
      innovation_(Eigen::VectorXd::Zero(joints)),
      innovation_variance_(measurement_variance_),
      F_(IntegratorChain::Matrix::Identity()),
      K_(IntegratorChain::Vector::Zero()) {}

void JointKalmanFilters::start(const Eigen::Ref<const Eigen::VectorXd>& q) {
  x_.setZero();
  x_.row(0) = q.transpose();
  innovation_.setZero();
  chain_.restart();
}

void JointKalmanFilters::step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q) {
  const double h = dt_s / chain_.period_s();
  F_ = chain_.transition(h);
  K_ = chain_.step(h);
  // K_0 = P⁻_00 / (P⁻_00 + r), so S = P⁻_00 + r = r / (1 − K_0).
  innovation_variance_ = measurement_variance_ / (1.0 - K_(0));
  correct(q);
}

void JointKalmanFilters::step_like(const JointKalmanFilters& stepped,
                                   const Eigen::Ref<const Eigen::VectorXd>& q) {
  F_ = stepped.F_;
  K_ = stepped.K_;
  innovation_variance_ = stepped.innovation_variance_;
  correct(q);
}

void JointKalmanFilters::correct(const Eigen::Ref<const Eigen::VectorXd>& q) {
  for (Eigen::Index j = 0; j < x_.cols(); ++j) {
    // Predict x⁻ = F x, correct x = x⁻ + K (q - x⁻_0).
    IntegratorChain::Vector x = F_ * x_.col(j);
    innovation_(j) = q(j) - x(0);
    x += K_ * innovation_(j);
    x_.col(j) = x;
  }
}

void JointKalmanFilters::set_acceleration(Eigen::Index j, double ddq) {
  x_(2, j) = ddq / (to_velocity_ * to_velocity_);
  x_.col(j).tail(IntegratorChain::kStates - 3).setZero();
}

void JointKalmanFilters::add_acceleration(Eigen::Index j, double delta) {
  x_(2, j) += delta / (to_velocity_ * to_velocity_);
}

}  // namespace wbi::estimation
