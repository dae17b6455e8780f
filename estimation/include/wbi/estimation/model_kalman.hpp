// Joint velocity and acceleration from the encoders fused with the
// acceleration a model predicts, e.g. the forward dynamics
// q̈_model = [M⁻¹(Bτ − h + Σ Jᵀf)]_joints with τ the commanded torques and f
// the estimated contact wrenches (components/estimator, `accelerations: model`).
// Not one of make_estimator()'s methods: it needs that input at every sample.
//
// Per joint the Kalman filter of integrator_chain.hpp runs on the model's
// error instead of the acceleration itself:
//
//   q̈ = u + e,   u the model's acceleration (a known input, held over each
//                interval), e its error, whose derivative (model order 2) or
//                second derivative (3) is white noise of density σ_w².
//
// The input enters the chain's acceleration state as a known change (Δu added
// when it is set; JointKalmanFilters::add_acceleration), so the filter
// follows the model at once and only has to find its error in the encoder
// innovations. A model error varies far slower than the acceleration, hence a
// small σ_w: less noise than a filter that must find all of q̈ in the
// encoders, and no lag where the model is right. Without any input (u = 0) it
// is the `kalman` method with that σ_w.
//
// At sample k: update(q_k) predicts with u_(k−1) held over the interval and
// corrects with q_k; set_model_acceleration(u_k) then makes the estimate
// u_k + ê_k (no lag where the model is right) and holds u_k over the next
// interval. Without an input after a sample, the last one is held.
#pragma once

#include "wbi/estimation/derivative_estimator.hpp"
#include "wbi/estimation/joint_kalman_filters.hpp"

namespace wbi::estimation {

struct ModelKalmanParameters {
  // Of the model's error: 2 a random walk, 3 (default) an integrated one, so
  // that a drifting error is followed without a steady lag. σ_w tuned on iCub 3
  // balancing in MuJoCo (components/estimator/README.md): 0.3, 1, 3, 10 gave
  // 0.240, 0.253, 0.279, 0.322 rad/s² of q̈ error (legs and torso, below 20 Hz).
  int model_order = 3;
  double resolution_counts = 16384.0;  // encoder counts per revolution (2^14)
  double process_noise = 0.3;          // σ_w of the model's error, rad/s^(order+1)/√Hz
};

class ModelKalmanEstimator final : public DerivativeEstimator {
 public:
  ModelKalmanEstimator(Eigen::Index joints, const ModelKalmanParameters& params,
                       const StreamParameters& stream = {});
  const char* method() const override { return "model-kalman"; }
  // The model's joint acceleration (rad/s², size joints()) at the last
  // update()'s sample: acceleration() follows it at once, and it is held over
  // the interval to the next sample. A non-finite entry leaves that joint's
  // last input (counted). Throws std::invalid_argument for a wrong size.
  // Never allocates.
  void set_model_acceleration(const Eigen::Ref<const Eigen::VectorXd>& model_ddq);
  // Entries of set_model_acceleration() that were not finite.
  std::uint64_t non_finite_inputs() const { return non_finite_inputs_; }

 private:
  void start(const Eigen::Ref<const Eigen::VectorXd>& q) override;
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
            Eigen::VectorXd& ddq) override;

  JointKalmanFilters filters_;
  Eigen::VectorXd applied_;  // u in the filters' acceleration state, rad/s²
  std::uint64_t non_finite_inputs_ = 0;
};

}  // namespace wbi::estimation
