// `split-kalman`: separate estimators for the velocity and the acceleration,
// both integrator-chain Kalman filters (joint_kalman_filters.hpp) on the same
// samples, because one filter cannot serve both outputs:
//
// * dq: one filter whose bandwidth is set for the velocity alone, low enough
//   to stay safe in a stiff PD loop (see README.md, "Closed loop").
// * ddq: a bank of filters with process noises spaced geometrically between
//   a minimum and a maximum, blended per joint by the likelihood of their
//   recent innovations (multiple-model adaptive estimation, Magill 1965;
//   Bar-Shalom, Li and Kirubarajan 2001, §11.6) with a forgetting time:
//     ℓ_i ← λ ℓ_i + ν_i²/S_i + ln S_i,   λ = exp(−Δt / memory)
//     w_i ∝ exp(−ℓ_i / 2),               ddq = Σ w_i ddq_i
//   A slow joint, where quantisation noise dominates, follows the quiet
//   low-noise model; a fast one (a wrist waving), where lag dominates, the
//   agile one. The quantisation noise in ddq grows with the bandwidth to the
//   power 2.5, so no single bandwidth suits both.
#pragma once

#include <vector>

#include "wbi/estimation/derivative_estimator.hpp"
#include "wbi/estimation/joint_kalman_filters.hpp"

namespace wbi::estimation {

struct SplitKalmanParameters {
  double resolution_counts = 16384.0;      // encoder counts per revolution (2^14)
  int velocity_order = 3;                  // model order of the dq filter
  double velocity_process_noise = 300.0;   // σ_w of the dq filter, rad/s^(order+1)/√Hz
  double velocity_cutoff_hz = 0.0;         // first-order low-pass on dq, Hz; 0: none
  int acceleration_order = 3;              // model order of the ddq filters
  double acceleration_noise_min = 30.0;    // σ_w of the quietest ddq filter
  double acceleration_noise_max = 2000.0;  // σ_w of the most agile ddq filter
  int acceleration_models = 4;             // filters in the ddq bank (1: the quietest only)
  double acceleration_memory_s = 0.1;      // forgetting time of the model likelihoods
};

class SplitKalmanEstimator final : public DerivativeEstimator {
 public:
  SplitKalmanEstimator(Eigen::Index joints, const SplitKalmanParameters& params,
                       const StreamParameters& stream = {});
  const char* method() const override { return "split-kalman"; }
  const IntegratorChain& velocity_model() const { return velocity_filters_.model(); }
  // The bank's current weights, (models × joints), columns sum to 1.
  const Eigen::MatrixXd& acceleration_weights() const { return weights_; }

 private:
  void start(const Eigen::Ref<const Eigen::VectorXd>& q) override;
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
            Eigen::VectorXd& ddq) override;

  JointKalmanFilters velocity_filters_;
  double velocity_cutoff_hz_;
  Eigen::VectorXd velocity_;  // (joints) the dq filter's output before the low-pass
  std::vector<JointKalmanFilters> acceleration_filters_;
  double memory_s_;
  Eigen::MatrixXd log_likelihood_;  // (models × joints) −2 ln L with forgetting
  Eigen::MatrixXd weights_;         // (models × joints)
};

}  // namespace wbi::estimation
