// Backward differences, the baseline: dq_k = (q_k - q_(k-1)) / Δt_k and
// ddq_k = (dq_k - dq_(k-1)) / ((Δt_k + Δt_(k-1)) / 2), each optionally
// smoothed by a first-order low-pass with cut-off f_c (see low_pass_filter.hpp).
// Without low-pass it is exact for velocity of lines and acceleration of parabolas.
#pragma once

#include "wbi/estimation/derivative_estimator.hpp"

namespace wbi::estimation {

struct BackwardDifferenceParameters {
  double cutoff_hz = 0.0;  // low-pass cut-off, Hz; 0: no low-pass
};

class BackwardDifferenceEstimator final : public DerivativeEstimator {
 public:
  BackwardDifferenceEstimator(Eigen::Index joints, const BackwardDifferenceParameters& params,
                              const StreamParameters& stream = {});
  const char* method() const override { return "backward-difference"; }

 private:
  void start(const Eigen::Ref<const Eigen::VectorXd>& q) override;
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
            Eigen::VectorXd& ddq) override;

  BackwardDifferenceParameters params_;
  Eigen::VectorXd q_previous_;  // (joints) last used positions, rad
  double dt_previous_ = 0.0;    // interval before the last used sample, s; 0: none yet
};

}  // namespace wbi::estimation
