// First-order low-pass filter on source stamps, for joint torques and
// force/torque wrenches: y_k = y_(k-1) + (1 - exp(-2π f_c Δt_k)) (x_k - y_(k-1)),
// the exact discretisation of τ dy/dt = x - y (τ = 1/(2π f_c)) for an input
// that changes to x_k just after the previous sample. Works with any Δt.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "wbi/estimation/derivative_estimator.hpp"
#include "wbi/estimation/stamp_monitor.hpp"

namespace wbi::estimation {

// The smoothing factor 1 - exp(-2π f_c Δt) in [0, 1]; 1 (no filtering) when cutoff_hz is 0.
double low_pass_gain(double cutoff_hz, double dt_s);

class LowPassFilter {
 public:
  // size > 0 values; cutoff_hz >= 0, 0 passes the input through.
  // Throws std::invalid_argument otherwise.
  LowPassFilter(Eigen::Index size, double cutoff_hz, const StreamParameters& stream = {});

  // Feeds x (size size()) sampled at stamp_ns. The first sample (and the first
  // after a gap longer than max_gap) sets the output to x; ignored samples
  // leave it unchanged. Throws std::invalid_argument when x has the wrong size.
  SampleStatus update(std::int64_t stamp_ns, const Eigen::Ref<const Eigen::VectorXd>& x);
  void reset() { stamps_.reset(); }

  const Eigen::VectorXd& value() const { return y_; }
  Eigen::Index size() const { return y_.size(); }
  double cutoff_hz() const { return cutoff_hz_; }
  const StampCounters& stamp_counters() const { return stamps_.counters(); }
  void reset_counters() { stamps_.reset_counters(); }

 private:
  double cutoff_hz_;
  StampMonitor stamps_;
  Eigen::VectorXd y_;
};

}  // namespace wbi::estimation
