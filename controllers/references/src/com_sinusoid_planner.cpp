// The controller type `com_sinusoid`: the balancing experiments' CoM reference
// (com_sinusoid.hpp) as a planner chained in the balancer's own host (its
// output `com` feeds the balancer's input `com` in the same tick, before the
// balancer's update: no DDS, no tick of delay). The component of the same
// name publishes the same points on a topic from its own process.
#include <cstdio>

#include <wbi/controllers/com_measures.hpp>
#include <wbi/controllers/com_sinusoid.hpp>
#include <wbi/controllers/controller.hpp>
#include <wbi/controllers/reference_generators.hpp>

namespace wbi::controllers {

namespace {

class ComSinusoidPlanner final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override {
    return {{.name = "amplitude",
             .unit = "m",
             .default_value = {0.05},
             .min = 0.0,
             .max = 1.0,
             .live = false},
            {.name = "frequency_hz",
             .unit = "Hz",
             .default_value = {0.2},
             .min = 0.0,
             .max = 10.0,
             .live = false},
            {.name = "settle_s",
             .unit = "s",
             .help = "the measured CoM is the reference until then",
             .default_value = {0.5},
             .min = 0.0,
             .max = 600.0,
             .live = false},
            {.name = "direction",
             .help = "the swing's direction (world frame; normalised)",
             .default_value = {0.0, 1.0, 0.0},
             .size = 3,
             .live = false},
            {.name = "left_sole", .live = false, .text = true, .text_default = "l_sole"},
            {.name = "right_sole", .live = false, .text = true, .text_default = "r_sole"}};
  }
  std::vector<ReferenceSpec> outputs() const override {
    return {
        {.name = "com", .unit = "m", .help = "CoM position, velocity, acceleration", .size = 3}};
  }
  void bind_outputs(std::span<ReferenceOutput* const> outputs) override { output_ = outputs[0]; }
  bool commands_joints() const override { return false; }

  void configure(WholeBodyInterface& robot, const ParameterTable& parameters) override {
    robot_ = &robot;
    state_ = RobotState(robot.dofs());
    configured_.amplitude = parameters.value(parameters.index("amplitude"));
    configured_.frequency_hz = parameters.value(parameters.index("frequency_hz"));
    configured_.settle_s = parameters.value(parameters.index("settle_s"));
    const auto d = parameters.values(parameters.index("direction"));
    const Eigen::Vector3d direction(d[0], d[1], d[2]);
    if (direction.norm() == 0.0) {
      throw Error(parameters.owner() + ": direction takes 3 values, not all zero");
    }
    configured_.direction = direction.normalized();
    left_ = robot.frame_index(parameters.text(parameters.index("left_sole")));
    right_ = robot.frame_index(parameters.text(parameters.index("right_sole")));
  }
  // Its time starts at its activation's state (as the component's at its first).
  void activate(const RobotState& measured) override {
    sinusoid_ = configured_;
    start_ns_ = measured.stamp.source_ns;
    last_stamp_ns_ = -1;
  }
  // One point for the state of this tick, at its stamp; none for a state
  // answered already. No allocation.
  bool update(double /*time_s*/, double /*period_s*/) override {
    robot_->state().read_robot_state(state_, ReadMode::latest);
    if (state_.stamp.source_ns == last_stamp_ns_) {
      return false;
    }
    last_stamp_ns_ = state_.stamp.source_ns;
    const double t = 1e-9 * static_cast<double>(state_.stamp.source_ns - start_ns_);
    sinusoid_.follow(
        t, [&] { return measured_com(*robot_, state_); },
        [&] { return feet_center(*robot_, state_, left_, right_, sole_pose_); });
    Eigen::Vector3d x, v, a;
    sinusoid_.at(t, x, v, a);
    output_->write(state_.stamp.source_ns, {x.data(), 3}, {v.data(), 3}, {a.data(), 3});
    return true;
  }
  const Eigen::VectorXd& command() const override { return none_; }

 private:
  WholeBodyInterface* robot_ = nullptr;
  ReferenceOutput* output_ = nullptr;
  RobotState state_;
  ComSinusoid sinusoid_, configured_;
  int left_ = -1, right_ = -1;
  Transform sole_pose_ = Transform::Identity();
  std::int64_t start_ns_ = 0, last_stamp_ns_ = -1;
  Eigen::VectorXd none_;  // it commands no joint
};

}  // namespace

void register_reference_planners(ControllerRegistry& registry) {
  registry.add<ComSinusoidPlanner>(
      "com_sinusoid",
      "a CoM reference for a balancer in the same host, chained (inputs: {com: NAME}): the "
      "measured CoM while settling, then a sinusoid between the feet");
}

}  // namespace wbi::controllers
