// Adaptive-window least-squares derivative estimation (Janabi-Sharifi, Hayward
// and Chen, "Discrete-time adaptive windowing for velocity estimation",
// IEEE TCST 8(6), 2000), as the original whole-body interface used it:
// velocity from a line, acceleration from a parabola, each fitted over the
// longest window of newest samples (at most N) whose samples all lie within
// D of the fit. See README.md for the formulas.
#pragma once

#include <vector>

#include "wbi/estimation/derivative_estimator.hpp"

namespace wbi::estimation {

struct AdaptiveWindowParameters {
  int velocity_window = 16;      // N of the linear fit, samples, >= 2
  int acceleration_window = 25;  // N of the quadratic fit, samples, >= 3
  double threshold_rad = 1.0;    // D, rad, > 0
};

class AdaptiveWindowEstimator final : public DerivativeEstimator {
 public:
  AdaptiveWindowEstimator(Eigen::Index joints, const AdaptiveWindowParameters& params,
                          const StreamParameters& stream = {});
  const char* method() const override { return "adaptive-window"; }

 private:
  void start(const Eigen::Ref<const Eigen::VectorXd>& q) override;
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
            Eigen::VectorXd& ddq) override;

  void push(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q);
  void update_fit_matrices();
  // Slope (rad/period) of the longest linear fit within the threshold; y newest first.
  double linear_slope(const Eigen::VectorXd& y) const;
  // Second-order coefficient (rad/period²) of the longest quadratic fit within the threshold.
  double quadratic_curvature(const Eigen::VectorXd& y) const;

  AdaptiveWindowParameters params_;
  Eigen::Index capacity_;       // max(velocity_window, acceleration_window)
  Eigen::MatrixXd q_history_;   // (capacity × joints) ring buffer of positions, rad
  Eigen::VectorXd dt_history_;  // (capacity) interval before each stored sample, s
  Eigen::Index newest_ = 0;     // ring index of the newest sample
  Eigen::Index count_ = 0;      // samples stored
  Eigen::VectorXd tau_;  // (capacity) time of the i-th newest sample minus the newest, periods
  Eigen::VectorXd y_;    // (capacity) one joint's positions minus the newest, newest first
  // Inverse normal matrices of the fits over the n newest samples, index n;
  // shared by all joints because they share the stamps.
  std::vector<Eigen::Matrix2d> linear_inverse_;
  std::vector<Eigen::Matrix3d> quadratic_inverse_;
};

}  // namespace wbi::estimation
