// The controller type `walking_planner` (walking_planner.hpp): a WalkingPlan
// under the controller contract, modelled on com_sinusoid's planner. Its time
// is the state's source time since its activation's state.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include <wbi/controllers/controller.hpp>
#include <wbi/controllers/walking_plan.hpp>
#include <wbi/controllers/walking_planner.hpp>

namespace wbi::controllers {

namespace {

using walking::Foot;
using walking::FootPose;
using walking::WalkingParameters;
using walking::WalkingPlan;

constexpr double kDegree = std::numbers::pi / 180.0;

// WalkingParameters's numeric fields, by their names, in the order parameters() declares them.
struct Field {
  const char* name;
  const char* unit;
  double WalkingParameters::*member;
  double min, max;
};
constexpr Field kFields[] = {
    {"single_support_s", "s", &WalkingParameters::single_support_s, 0.05, 10.0},
    {"double_support_s", "s", &WalkingParameters::double_support_s, 0.01, 10.0},
    {"final_double_support_s", "s", &WalkingParameters::final_double_support_s, 0.01, 10.0},
    {"step_height", "m", &WalkingParameters::step_height, 0.001, 0.5},
    {"gravity", "m/s^2", &WalkingParameters::gravity, 0.1, 100.0},
    {"max_step_forward", "m", &WalkingParameters::max_step_forward, 0.001, 2.0},
    {"max_step_backward", "m", &WalkingParameters::max_step_backward, 0.001, 2.0},
    {"max_step_lateral", "m", &WalkingParameters::max_step_lateral, 0.001, 2.0},
    {"max_step_turn", "rad", &WalkingParameters::max_step_turn, 0.001, 3.0},
    {"min_step_width", "m", &WalkingParameters::min_step_width, 0.001, 2.0}};

class WalkingPlanner final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override {
    const WalkingParameters defaults;
    std::vector<ParameterSpec> specs;
    for (const Field& field : kFields) {
      specs.push_back({.name = field.name,
                       .unit = field.unit,
                       .default_value = {defaults.*field.member},
                       .min = field.min,
                       .max = field.max,
                       .live = false});
    }
    specs.push_back({.name = "com_height",
                     .unit = "m",
                     .help = "z_c of the LIPM; default: the CoM above the soles at activation",
                     .min = 0.05,
                     .max = 3.0,
                     .live = false,
                     .optional = true});
    specs.push_back({.name = "step_width",
                     .unit = "m",
                     .help = "the soles' lateral distance; default: measured at activation",
                     .min = 0.01,
                     .max = 2.0,
                     .live = false,
                     .optional = true});
    specs.push_back({.name = "vrp_offset",
                     .unit = "m",
                     .help = "the VRP in each sole's frame (the support rectangle's middle)",
                     .default_value = {0.0, 0.0, 0.0},
                     .size = 3,
                     .min = -1.0,
                     .max = 1.0,
                     .live = false});
    specs.push_back({.name = "goal",
                     .unit = "m, m, deg",
                     .help = "[dx, dy, dyaw]: walk there from the feet's middle and heading; "
                             "each change plans a walk (refused while walking)",
                     .default_value = {0.0, 0.0, 0.0},
                     .size = 3,
                     .min = -720.0,
                     .max = 720.0});
    specs.push_back({.name = "start_after_s",
                     .unit = "s",
                     .help = "the configured goal is walked this long after activation",
                     .default_value = {1.0},
                     .min = 0.0,
                     .max = 3600.0,
                     .live = false});
    specs.push_back({.name = "left_sole", .live = false, .text = true, .text_default = "l_sole"});
    specs.push_back({.name = "right_sole", .live = false, .text = true, .text_default = "r_sole"});
    return specs;
  }
  std::vector<ReferenceSpec> outputs() const override {
    return {{.name = "walk",
             .unit = "m",
             .help = "DCM, CoM, left and right sole (x, y, z, yaw), contact weights "
                     "(walking_plan.hpp)",
             .size = walking::kWalkReferenceSize}};
  }
  void bind_outputs(std::span<ReferenceOutput* const> outputs) override { output_ = outputs[0]; }
  bool commands_joints() const override { return false; }

  void configure(WholeBodyInterface& robot, const ParameterTable& parameters) override {
    robot_ = &robot;
    state_ = RobotState(robot.dofs());
    left_ = robot.frame_index(parameters.text(parameters.index("left_sole")));
    right_ = robot.frame_index(parameters.text(parameters.index("right_sole")));
    for (std::size_t i = 0; i < std::size(kFields); ++i) {
      fields_[i] = parameters.index(kFields[i].name);
    }
    com_height_ = parameters.index("com_height");
    step_width_ = parameters.index("step_width");
    vrp_offset_ = parameters.index("vrp_offset");
    goal_index_ = parameters.index("goal");
    start_after_ = parameters.index("start_after_s");
    parameters_changed(parameters);
  }

  // Between two ticks (or while inactive: used at activation). No allocation.
  void parameters_changed(const ParameterTable& p) override {
    for (std::size_t i = 0; i < std::size(kFields); ++i) {
      configured_.*kFields[i].member = p.value(fields_[i]);
    }
    measure_com_height_ = !p.is_set(com_height_);
    measure_step_width_ = !p.is_set(step_width_);
    if (!measure_com_height_) configured_.com_height = p.value(com_height_);
    if (!measure_step_width_) configured_.step_width = p.value(step_width_);
    const auto offset = p.values(vrp_offset_);
    configured_.vrp_offset = {offset[0], offset[1], offset[2]};
    start_after_s_ = p.value(start_after_);
    const auto goal = p.values(goal_index_);
    const Eigen::Vector3d new_goal(goal[0], goal[1], goal[2]);
    if (new_goal != goal_) {
      goal_ = new_goal;
      goal_pending_ = active_;  // an active planner walks it at its next state
      goal_time_ = last_time_;
    }
  }

  // Stands on the measured feet and CoM; the deploy file's goal waits start_after_s.
  void activate(const RobotState& measured) override {
    const FootPose left = walking::measured_sole(*robot_, measured, left_);
    const FootPose right = walking::measured_sole(*robot_, measured, right_);
    Eigen::Vector3d com;
    robot_->com(measured.q, measured.world_H_base, com);
    WalkingParameters p = configured_;
    if (measure_com_height_) {
      p.com_height = com.z() - 0.5 * (left.position.z() + right.position.z());
    }
    if (measure_step_width_) {
      // Across the feet's mean heading.
      const double heading =
          right.yaw + 0.5 * std::remainder(left.yaw - right.yaw, 2.0 * std::numbers::pi);
      const Eigen::Vector3d apart = left.position - right.position;
      p.step_width = std::abs(-std::sin(heading) * apart.x() + std::cos(heading) * apart.y());
    }
    plan_.emplace(p);  // throws wbi::Error naming a value out of range (the host says why)
    plan_->stand(0.0, left, right, com);
    start_ns_ = measured.stamp.source_ns;
    last_stamp_ns_ = -1;
    last_time_ = 0.0;
    active_ = true;
    goal_pending_ = goal_ != Eigen::Vector3d::Zero();
    goal_time_ = start_after_s_;
    walk_begin_ = 0.0;
  }
  void deactivate() override { active_ = false; }

  // One point for the state of this tick, at its stamp; none for a state
  // answered already. Allocates nothing but when a goal is planned or refused.
  bool update(double /*time_s*/, double /*period_s*/) override {
    robot_->state().read_robot_state(state_, ReadMode::latest);
    if (state_.stamp.source_ns == last_stamp_ns_) {
      return false;
    }
    last_stamp_ns_ = state_.stamp.source_ns;
    last_time_ = 1e-9 * static_cast<double>(state_.stamp.source_ns - start_ns_);
    if (goal_pending_ && last_time_ >= goal_time_) {
      goal_pending_ = false;
      walk_to_goal(last_time_);
    }
    plan_->sample(last_time_, reference_);
    output_->write(state_.stamp.source_ns,
                   {reference_.position.data(), walking::kWalkReferenceSize},
                   {reference_.velocity.data(), walking::kWalkReferenceSize},
                   {reference_.acceleration.data(), walking::kWalkReferenceSize});
    return true;
  }
  const Eigen::VectorXd& command() const override { return none_; }

  void progress(char* line, std::size_t size) const override {
    if (!plan_) {
      std::snprintf(line, size, "not active");
      return;
    }
    const WalkingParameters& p = plan_->parameters();
    const int steps = static_cast<int>(plan_->footsteps().size());
    const double tau = last_time_ - walk_begin_;
    if (!plan_->walking(last_time_)) {
      std::snprintf(line, size, "standing; %d steps walked", steps_walked());
    } else if (tau < p.final_double_support_s) {
      std::snprintf(line, size, "double support before step 1 of %d", steps);
    } else {
      // Phases after the first double support: single support, double support, per step.
      const double cycle = p.single_support_s + p.double_support_s;
      const int k = std::min(steps - 1, static_cast<int>((tau - p.final_double_support_s) / cycle));
      const double in_cycle = tau - p.final_double_support_s - k * cycle;
      if (in_cycle < p.single_support_s) {
        std::snprintf(line, size, "single support, step %d of %d (%s foot swinging)", k + 1, steps,
                      plan_->footsteps()[k].foot == Foot::left ? "left" : "right");
      } else {
        std::snprintf(line, size, "double support after step %d of %d", k + 1, steps);
      }
    }
  }

  std::string summary() const override {
    char text[256];
    std::snprintf(text, sizeof text,
                  "walking_planner: %d steps walked of %d planned in %d walks; %.3f m planned, "
                  "average speed %.3f m/s (%.1f s); %d goals refused",
                  steps_walked(), steps_planned_, walks_, distance_,
                  walk_s_ > 0 ? distance_ / walk_s_ : 0.0, walk_s_, refused_);
    return text;
  }

 private:
  // Earlier walks' steps, and the current one's that touched down by now.
  int steps_walked() const {
    if (!plan_ || walks_ == 0) {
      return 0;
    }
    const WalkingParameters& p = plan_->parameters();
    const int steps = static_cast<int>(plan_->footsteps().size());
    // Step k touches down at T_f + k T_ss + (k − 1) T_ds after the walk began.
    const double cycle = p.single_support_s + p.double_support_s;
    const double since = last_time_ - walk_begin_ - p.final_double_support_s + p.double_support_s;
    const int done = std::clamp(static_cast<int>(std::floor(since / cycle)), 0, steps);
    return steps_before_ + done;
  }

  void walk_to_goal(double t) {
    const int walked = steps_walked();
    const std::string why = plan_->walk_to(t, goal_.x(), goal_.y(), goal_.z() * kDegree);
    if (!why.empty()) {
      ++refused_;
      std::printf("walking_planner: goal refused: %s\n", why.c_str());
    } else if (!plan_->walking(t)) {
      std::printf("walking_planner: goal [%g, %g, %g deg]: there already\n", goal_.x(), goal_.y(),
                  goal_.z());
    } else {
      const int steps = static_cast<int>(plan_->footsteps().size());
      steps_before_ = walked;
      ++walks_;
      steps_planned_ += steps;
      distance_ += std::hypot(goal_.x(), goal_.y());
      walk_s_ += plan_->end_time() - t;
      walk_begin_ = t;
      std::printf(
          "walking_planner: goal [%g m, %g m, %g deg] planned at t = %.3f s: %d steps, "
          "ends at t = %.3f s\n",
          goal_.x(), goal_.y(), goal_.z(), t, steps, plan_->end_time());
    }
    std::fflush(stdout);
  }

  WholeBodyInterface* robot_ = nullptr;
  ReferenceOutput* output_ = nullptr;
  RobotState state_;
  std::optional<WalkingPlan> plan_;
  walking::WalkingReference reference_;
  WalkingParameters configured_;
  bool measure_com_height_ = true, measure_step_width_ = true;
  int left_ = -1, right_ = -1;
  std::array<std::size_t, std::size(kFields)> fields_{};
  std::size_t com_height_ = 0, step_width_ = 0, vrp_offset_ = 0, goal_index_ = 0, start_after_ = 0;
  Eigen::Vector3d goal_ = Eigen::Vector3d::Zero();
  bool goal_pending_ = false, active_ = false;
  double goal_time_ = 0.0, start_after_s_ = 1.0, last_time_ = 0.0, walk_begin_ = 0.0;
  std::int64_t start_ns_ = 0, last_stamp_ns_ = -1;
  int walks_ = 0, steps_planned_ = 0, steps_before_ = 0, refused_ = 0;
  double distance_ = 0.0, walk_s_ = 0.0;
  Eigen::VectorXd none_;  // it commands no joint
};

}  // namespace

void register_walking_planner(ControllerRegistry& registry) {
  registry.add<WalkingPlanner>(
      "walking_planner",
      "walking references (DCM, CoM, feet, contact weights) for a walking controller in the same "
      "host, chained (inputs: {walk: NAME}); goal = [dx, dy, dyaw_deg] walks there");
}

}  // namespace wbi::controllers
