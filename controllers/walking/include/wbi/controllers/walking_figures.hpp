// The walking figures, gathered once per tick from the plan and the measured
// state: what a walk achieved, for the summary and the tests.
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>

#include "wbi/controllers/walking_qp.hpp"

namespace wbi::controllers::walking {

class WalkingFigures {
 public:
  // fall_height: the base below this height above the lower sole is a fall;
  // speed_distance: the forward speed is timed over this much of the CoM's travel.
  void reset(double fall_height, double speed_distance);
  // t: the state's time since activation. No allocation.
  void add(double t, const WalkingTargets& plan, const WalkingQp& qp);

  bool fell() const { return fall_time_ >= 0.0; }
  double fall_time() const { return fall_time_; }
  int steps() const { return steps_; }
  double walked_distance() const;  // the CoM's, horizontal, from the first step's start [m]
  double walking_time() const;     // from the first foot's unloading to the last landing [s]
  double average_speed() const;    // [m/s]
  // Over the first speed_distance of the walk; < 0 when the CoM never got that far.
  double forward_speed() const;
  double dcm_rms() const;                                              // horizontal [m]
  double com_rms() const;                                              // [m]
  double max_slip() const { return max_slip_; }                        // per stance, horizontal [m]
  double max_touchdown_error() const { return max_touchdown_error_; }  // [m]
  double min_stance_force() const { return min_stance_force_; }  // single support, planned [N]
  // The figures, one per line.
  std::string text() const;

 private:
  double fall_height_ = 0.0, fall_time_ = -1.0, speed_distance_ = 1.0, speed_time_ = -1.0;
  std::uint64_t ticks_ = 0;
  double dcm_squared_ = 0.0, com_squared_ = 0.0;
  bool walking_ = false;
  double walk_start_t_ = 0.0, walk_end_t_ = 0.0;
  Eigen::Vector2d walk_start_com_ = Eigen::Vector2d::Zero(),
                  walk_end_com_ = Eigen::Vector2d::Zero();
  std::array<double, 2> last_weight_{1.0, 1.0};
  std::array<Eigen::Vector3d, 2> lift_off_, anchor_;
  std::array<bool, 2> anchored_{false, false};
  int steps_ = 0;
  // Step length: how far the feet's middle moved from one touch-down to the next.
  Eigen::Vector2d last_touchdown_middle_ = Eigen::Vector2d::Zero();
  double step_length_sum_ = 0.0, last_touchdown_t_ = -1.0, step_duration_sum_ = 0.0;
  int timed_steps_ = 0;
  double max_slip_ = 0.0, max_touchdown_error_ = 0.0, min_stance_force_ = 0.0;
  bool single_support_seen_ = false;
};

}  // namespace wbi::controllers::walking
