// The interface every joint velocity/acceleration estimator implements.
//
// A component wraps it directly: construct once (sizes fixed), call update()
// with each sample's source stamp and positions, read velocity() and
// acceleration(), publish stamp_counters() as warnings. update() never
// allocates (a test built with EIGEN_RUNTIME_NO_MALLOC checks every method).
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "wbi/estimation/stamp_monitor.hpp"

namespace wbi::estimation {

// Parameters every method has.
struct StreamParameters {
  double sample_rate_hz = 1000.0;  // nominal rate: counts dropped samples, tunes some methods
  double max_gap_s = 0.1;          // a longer interval between stamps restarts the estimator
};

class DerivativeEstimator {
 public:
  // joints > 0. Throws std::invalid_argument on bad parameters.
  DerivativeEstimator(Eigen::Index joints, const StreamParameters& stream);
  virtual ~DerivativeEstimator() = default;
  DerivativeEstimator(const DerivativeEstimator&) = delete;
  DerivativeEstimator& operator=(const DerivativeEstimator&) = delete;

  // Feeds the positions q (size joints(), rad) sampled at source stamp stamp_ns.
  // Ignored samples (duplicated or older stamp, NaN/inf in q) leave the
  // estimates unchanged; the first sample, and the first after a gap longer
  // than max_gap, restart the estimator with zero velocity and acceleration.
  // Throws std::invalid_argument when q has the wrong size.
  SampleStatus update(std::int64_t stamp_ns, const Eigen::Ref<const Eigen::VectorXd>& q);

  // Forgets the history: the next sample is treated as the first. Counters are kept.
  void reset();

  const Eigen::VectorXd& velocity() const { return dq_; }       // rad/s, size joints()
  const Eigen::VectorXd& acceleration() const { return ddq_; }  // rad/s², size joints()
  Eigen::Index joints() const { return dq_.size(); }
  const StampCounters& stamp_counters() const { return stamps_.counters(); }
  void reset_counters() { stamps_.reset_counters(); }
  double sample_rate_hz() const { return stamps_.sample_rate_hz(); }

  // The method name, as given to make_estimator().
  virtual const char* method() const = 0;

 protected:
  // Restart from q alone (history forgotten). dq and ddq are already zero.
  virtual void start(const Eigen::Ref<const Eigen::VectorXd>& q) = 0;
  // The next sample, dt_s > 0 seconds after the previous used one. Writes dq and ddq.
  virtual void step(double dt_s, const Eigen::Ref<const Eigen::VectorXd>& q, Eigen::VectorXd& dq,
                    Eigen::VectorXd& ddq) = 0;
  // For an input between samples (model_kalman.hpp): joint j's acceleration estimate.
  void set_acceleration(Eigen::Index j, double ddq) { ddq_[j] = ddq; }

 private:
  StampMonitor stamps_;
  Eigen::VectorXd dq_;
  Eigen::VectorXd ddq_;
};

}  // namespace wbi::estimation
