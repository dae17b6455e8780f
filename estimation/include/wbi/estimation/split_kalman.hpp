// `split-kalman`: separate estimators for the velocity and the acceleration,
// both integrator-chain Kalman filters (joint_kalman_filters.hpp) on the same
// samples, because one filter cannot serve both outputs:
//
// * dq: one filter whose bandwidth is set for the velocity alone, low enough
//   to stay safe in a stiff PD loop (see README.md, "Closed loop").
// * ddq: a bank of filters from quiet to agile blended per joint by the
//   likelihood of their innovations (acceleration_bank.hpp). A slow joint,
//   where quantisation noise dominates, follows the quiet model; a fast one
//   (a wrist waving), where lag dominates, the agile one. The quantisation
//   noise in ddq grows with the bandwidth to the power 2.5, so no single
//   bandwidth suits both.
// * stick anticipation (stick_duration_s > 0): Coulomb friction makes a
//   joint stick for a few ms at each velocity reversal, and its acceleration
//   jumps towards zero — too briefly for the positions to show it before it
//   is over. A second bank assumes the stick: when the first bank's velocity
//   of a joint is about to reverse (decelerating within stick_velocity of
//   zero) or has just changed sign (whatever the dq filter's settings), its
//   filters scale that joint's acceleration by stick_fraction, hold it for
//   stick_duration_s, then return it to the value it had with time constant
//   stick_release_s. The two banks are blended per joint by the likelihood
//   of their predictions over stick_memory_s (long enough to span several
//   reversals), so a joint that sticks follows the second bank and one that
//   does not (or a robot without friction) the first.
#pragma once

#include <optional>
#include <vector>

#include "wbi/estimation/acceleration_bank.hpp"
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
  double stick_duration_s = 0.007;         // assumed stick at a reversal, s; 0: no anticipation
  double stick_fraction = 0.15;            // acceleration kept while stuck, [0, 1]
  double stick_release_s = 0.004;          // time constant of the return after it, s; 0: a jump
  double stick_velocity = 0.01;  // rad/s: slowing below it = reversing; 0: sign change only
  double stick_memory_s = 0.5;   // forgetting time of the stick/no-stick likelihoods
};

class SplitKalmanEstimator final : public DerivativeEstimator {
 public:
  SplitKalmanEstimator(Eigen::Index joints, const SplitKalmanParameters& params,
                       const StreamParameters& stream = {});
  const char* method() const override { return "split-kalman"; }
  const IntegratorChain& velocity_model() const { return velocity_filters_.model(); }
  // The (non-sticking) bank's current weights, (models × joints), columns sum to 1.
  const Eigen::MatrixXd& acceleration_weights() const { return moving_.weights(); }
  // Per joint, the weight of the sticking bank (0 without stick anticipation).
  const Eigen::VectorXd& stick_weights() const { return stick_weight_; }

 private:
  void start(const Eigen::Ref<const Eigen::VectorXd>& q) override;
  void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
            Eigen::VectorXd& ddq) override;
  enum class StickPhase : unsigned char { kNone, kHolding, kReleasing };
  // Starts, holds and releases the sticking bank's assumed stick of each joint.
  void anticipate_sticks(double dt_s);
  void start_stick_at_reversal(Eigen::Index j);
  void release_stick(Eigen::Index j);

  JointKalmanFilters velocity_filters_;
  double velocity_cutoff_hz_;
  Eigen::VectorXd velocity_;           // (joints) the dq filter's output before the low-pass
  Eigen::VectorXd previous_velocity_;  // (joints) moving_'s velocity one sample earlier
  double memory_s_;
  AccelerationBank moving_;                   // no stick assumed
  std::optional<AccelerationBank> sticking_;  // sticks at reversals (stick_duration_s > 0)
  double stick_duration_s_;
  double stick_fraction_;
  double stick_release_s_;
  double stick_velocity_;
  double stick_memory_s_;
  std::vector<StickPhase> stick_phase_;  // (joints)
  Eigen::VectorXd stick_elapsed_s_;      // (joints) time since the assumed stick began
  Eigen::VectorXd stick_gap_;            // (joints) share of (1 − fraction) not yet returned
  Eigen::VectorXd reversal_sign_;        // (joints) sign of dq before the last reversal, 0: none
  Eigen::Matrix2Xd family_likelihood_;   // (2 × joints) −2 ln L of moving_, sticking_
  Eigen::VectorXd stick_weight_;         // (joints)
};

}  // namespace wbi::estimation
