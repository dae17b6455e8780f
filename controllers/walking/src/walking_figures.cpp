#include "wbi/controllers/walking_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wbi::controllers::walking {

void WalkingFigures::reset(double fall_height, double speed_distance) {
  *this = WalkingFigures{};
  fall_height_ = fall_height;
  speed_distance_ = speed_distance;
}

void WalkingFigures::add(double t, const WalkingTargets& plan, const WalkingQp& qp) {
  const auto& state = qp.state();
  const Eigen::Vector3d feet[2] = {qp.foot(Foot::left).position, qp.foot(Foot::right).position};
  const double ground = std::min(feet[0].z(), feet[1].z());
  if (!fell() && state.world_H_base(2, 3) - ground < fall_height_) {
    fall_time_ = t;
  }
  ++ticks_;
  dcm_squared_ += (qp.dcm() - plan.dcm).head<2>().squaredNorm();
  com_squared_ += (qp.com() - plan.com).squaredNorm();

  const bool walking = plan.contact_weight[0] < 1.0 || plan.contact_weight[1] < 1.0;
  if (walking) {
    if (!walking_ && steps_ == 0) {
      walk_start_t_ = t;
      walk_start_com_ = qp.com().head<2>();
    }
    walk_end_t_ = t;
    walk_end_com_ = qp.com().head<2>();
    if (speed_time_ < 0.0 && walked_distance() >= speed_distance_) {
      speed_time_ = t - walk_start_t_;
    }
  }
  walking_ = walking;

  for (int f = 0; f < 2; ++f) {
    const double w = plan.contact_weight[f];
    if (last_weight_[f] > 0.0 && w == 0.0) {
      lift_off_[f] = feet[f];
      anchored_[f] = false;
    }
    if (last_weight_[f] == 0.0 && w > 0.0) {
      ++steps_;
      const Eigen::Vector2d middle = 0.5 * (feet[0] + feet[1]).head<2>();
      if (steps_ > 1) {
        step_length_sum_ += (middle - last_touchdown_middle_).norm();
      }
      last_touchdown_middle_ = middle;
      max_touchdown_error_ =
          std::max(max_touchdown_error_, (feet[f] - plan.feet[f].position).norm());
      if (last_touchdown_t_ >= 0.0) {
        step_duration_sum_ += t - last_touchdown_t_;
        ++timed_steps_;
      }
      last_touchdown_t_ = t;
    }
    if (w > 0.0) {
      if (!anchored_[f]) {
        anchor_[f] = feet[f];
        anchored_[f] = true;
      }
      max_slip_ = std::max(max_slip_, (feet[f] - anchor_[f]).head<2>().norm());
    }
    last_weight_[f] = w;
  }
  for (int f = 0; f < 2; ++f) {
    if (plan.contact_weight[f] == 1.0 && plan.contact_weight[1 - f] == 0.0) {
      const double fz = qp.wrenches()[6 * f + 2];
      min_stance_force_ = single_support_seen_ ? std::min(min_stance_force_, fz) : fz;
      single_support_seen_ = true;
    }
  }
}

double WalkingFigures::walked_distance() const { return (walk_end_com_ - walk_start_com_).norm(); }

double WalkingFigures::walking_time() const { return walk_end_t_ - walk_start_t_; }

double WalkingFigures::average_speed() const {
  const double time = walking_time();
  return time > 0.0 ? walked_distance() / time : 0.0;
}

double WalkingFigures::forward_speed() const {
  return speed_time_ > 0.0 ? speed_distance_ / speed_time_ : -1.0;
}

double WalkingFigures::dcm_rms() const {
  return ticks_ > 0 ? std::sqrt(dcm_squared_ / static_cast<double>(ticks_)) : 0.0;
}

double WalkingFigures::com_rms() const {
  return ticks_ > 0 ? std::sqrt(com_squared_ / static_cast<double>(ticks_)) : 0.0;
}

std::string WalkingFigures::text() const {
  char speed_line[96];
  if (forward_speed() > 0.0) {
    std::snprintf(speed_line, sizeof speed_line, "forward speed over the first %.2f m: %.3f m/s",
                  speed_distance_, forward_speed());
  } else {
    std::snprintf(speed_line, sizeof speed_line,
                  "forward speed over the first %.2f m: none (the CoM never got that far)",
                  speed_distance_);
  }
  char text[896];
  std::snprintf(text, sizeof text,
                "steps: %d\n"
                "walked: %.3f m in %.2f s, average speed %.3f m/s\n"
                "%s\n"
                "step length (the feet's middle, touch-down to touch-down): %.3f m mean, step "
                "duration %.3f s mean\n"
                "dcm tracking rms: %.6f m\n"
                "com tracking rms: %.6f m\n"
                "largest stance foot slip: %.4f m\n"
                "largest touch-down position error: %.4f m\n"
                "smallest stance normal force (planned, single support): %.1f N\n"
                "falls: %s",
                steps_, walked_distance(), walking_time(), average_speed(), speed_line,
                timed_steps_ > 0 ? step_length_sum_ / timed_steps_ : 0.0,
                timed_steps_ > 0 ? step_duration_sum_ / timed_steps_ : 0.0, dcm_rms(), com_rms(),
                max_slip_, max_touchdown_error_, single_support_seen_ ? min_stance_force_ : 0.0,
                fell() ? "1" : "0");
  std::string result = text;
  if (fell()) {
    std::snprintf(text, sizeof text, " (at t = %.3f s)", fall_time_);
    result += text;
  }
  return result;
}

}  // namespace wbi::controllers::walking
