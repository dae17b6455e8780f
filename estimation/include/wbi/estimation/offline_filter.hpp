// Runs an estimator over a whole recorded trajectory (the `wbi estimate` loop).
#pragma once

#include <cstdint>

#include "wbi/estimation/derivative_estimator.hpp"
#include "wbi/estimation/trajectory_csv.hpp"

namespace wbi::estimation {

// Source stamp in ns of a time in seconds (rounded to the nearest ns).
std::int64_t stamp_from_seconds(double t_s);

// Resets `estimator`, feeds it every row of `samples` in file order and
// returns one row of estimates per input row; an ignored row (bad stamp,
// NaN) repeats the previous estimates. Throws std::invalid_argument when the
// estimator's size differs from the number of joint columns.
JointDerivatives estimate_offline(DerivativeEstimator& estimator, const JointSamples& samples);

}  // namespace wbi::estimation
