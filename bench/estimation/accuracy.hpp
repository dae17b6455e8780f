// Accuracy of an estimator against a ground-truth motion: RMSE and lag.
#pragma once

#include <Eigen/Core>

#include "motion.hpp"
#include "wbi/estimation/derivative_estimator.hpp"

namespace wbi::bench {

struct Estimates {
  Eigen::MatrixXd dq;   // (joints × samples)
  Eigen::MatrixXd ddq;  // (joints × samples)
};

// Feeds the whole recording to `estimator` (reset first).
void run_estimator(estimation::DerivativeEstimator& estimator, const EncoderRecording& recording,
                   Estimates& out);

enum class Derivative { velocity, acceleration };

// RMSE over all joints and samples after warm_up_s of estimate(t_k) against
// truth(t_k - lag_s): the error that remains once a pure delay is removed.
double shifted_rmse(const Motion& motion, const EncoderRecording& recording,
                    const Eigen::MatrixXd& estimate, Derivative derivative, double lag_s,
                    double warm_up_s);

struct Fit {
  double rmse;   // at zero lag
  double lag_s;  // the shift minimising the RMSE, in [-5, 60] ms
};

// RMSE at zero lag, and the lag: the shift that minimises shifted_rmse
// (1 ms grid, then golden-section refinement to ~10 µs).
Fit accuracy(const Motion& motion, const EncoderRecording& recording,
             const Eigen::MatrixXd& estimate, Derivative derivative, double warm_up_s);

using SampleMask = Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>;  // (joints × samples)

// The samples of each joint within [−before_s, +after_s] of a velocity
// reversal of the truth (a sign change of dq_true between two samples): where
// Coulomb friction makes the acceleration jump, and the estimators recover.
SampleMask near_velocity_reversals(const EncoderRecording& recording, double before_s,
                                   double after_s);

// RMSE at zero lag of estimate against truth (joints × samples, at the
// recording's stamps) over the samples after warm_up_s that `excluded` does
// not mark.
double rmse_outside(const EncoderRecording& recording, const Eigen::MatrixXd& estimate,
                    const Eigen::MatrixXd& truth, const SampleMask& excluded, double warm_up_s);

// A lower bound for estimators that must see an acceleration jump in the
// positions before they can follow it: the truth itself, except that after
// every jump of the true ddq by more than jump (rad/s², from one sample to
// the next) it keeps the value before the jump for `blind` samples.
Estimates truth_blind_to_jumps(const EncoderRecording& recording, double jump, int blind);

}  // namespace wbi::bench
