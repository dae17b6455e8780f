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

}  // namespace wbi::bench
