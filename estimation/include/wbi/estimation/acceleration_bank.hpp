// The acceleration part of `split-kalman`: a bank of integrator-chain Kalman
// filters (joint_kalman_filters.hpp) with process noises spaced geometrically
// from a minimum to a maximum, blended per joint by the likelihood of their
// recent innovations (multiple-model adaptive estimation, Magill 1965;
// Bar-Shalom, Li and Kirubarajan 2001, §11.6) with a forgetting factor λ:
//   ℓ_i ← λ ℓ_i + ν_i²/S_i + ln S_i,   w_i ∝ exp(−ℓ_i / 2),   ddq = Σ w_i ddq_i
// A bank can also be told that a joint sticks (stick()/slip()/recover()):
// every filter then scales that joint's acceleration, and brings it back,
// at once or along a ramp, when it slips.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "wbi/estimation/joint_kalman_filters.hpp"

namespace wbi::estimation {

struct AccelerationBankParameters {
  int order = 3;              // model order of every filter
  double counts = 16384.0;    // encoder counts per revolution
  double noise_min = 30.0;    // σ_w of the quietest filter
  double noise_max = 2000.0;  // σ_w of the most agile filter (>= noise_min)
  int models = 4;             // 1–8
};

class AccelerationBank {
 public:
  // Throws std::invalid_argument naming `method` on bad parameters.
  AccelerationBank(const char* method, Eigen::Index joints, const AccelerationBankParameters& p,
                   double period_s);

  void start(const Eigen::Ref<const Eigen::VectorXd>& q);
  // The next sample, dt_s > 0 after the previous one; forget = λ. Never allocates.
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, double forget);
  // The same sample as `stepped`, a bank of the same parameters and joints
  // that has just run step(): its filters' gains are reused (one Riccati
  // step per model for both banks). Use either this or step() on one bank.
  void step_like(const AccelerationBank& stepped, const Eigen::Ref<const Eigen::VectorXd>& q,
                 double forget);

  // Blended acceleration and velocity of joint j, rad/s² and rad/s.
  double acceleration(Eigen::Index j) const { return acceleration_(j); }
  double velocity(Eigen::Index j) const { return velocity_(j); }
  // Of the last step, joint j: Σ_i w_i (ν_i²/S_i + ln S_i) with the weights
  // before the sample, the bank's −2 ln likelihood of the sample (up to a
  // constant) as its blend predicted it.
  double innovation_score(Eigen::Index j) const { return innovation_score_(j); }
  // Current weights, (models × joints), columns sum to 1.
  const Eigen::MatrixXd& weights() const { return weights_; }

  // Joint j sticks: each filter's acceleration of j is scaled by `fraction`
  // (its higher derivatives zeroed).
  void stick(Eigen::Index j, double fraction);
  // Joint j slips: each filter's acceleration of j becomes `fraction` × the
  // one it had at stick() (higher derivatives zeroed; 1: all of it back)...
  void slip(Eigen::Index j, double fraction);
  // ...and then grows by `increment` × that acceleration per call (the rest
  // of a release ramp), its other states untouched.
  void recover(Eigen::Index j, double increment);

 private:
  // Likelihoods, weights and blend from the filters' innovations of this sample.
  void update_weights(double forget);
  void blend(Eigen::Index j);  // velocity_(j), acceleration_(j) from the weights

  std::vector<JointKalmanFilters> filters_;
  Eigen::MatrixXd log_likelihood_;         // (models × joints) −2 ln L with forgetting
  Eigen::MatrixXd weights_;                // (models × joints)
  Eigen::RowVectorXd best_;                // (joints) scratch: smallest −2 ln L
  Eigen::RowVectorXd total_;               // (joints) scratch: sum of the weights
  Eigen::MatrixXd acceleration_at_stick_;  // (models × joints) rad/s², set by stick()
  Eigen::VectorXd velocity_;               // (joints) blended, rad/s
  Eigen::VectorXd acceleration_;           // (joints) blended, rad/s²
  Eigen::VectorXd innovation_score_;       // (joints)
};

}  // namespace wbi::estimation
