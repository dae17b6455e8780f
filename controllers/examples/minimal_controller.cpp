// controllers/README.md, "Writing a controller": PD + gravity under the
// controller contract, whole, as a plugin of a lab's own project. Built here
// the way a lab builds it (wbi_add_plugin) and run by test_minimal_controller:
// hosted, switched to from hold and back, a gain changed while it runs.
#include <cstdio>

#include <wbi/controllers/controller.hpp>
#include <wbi/plugin.hpp>

namespace example {
using namespace wbi;
using namespace wbi::controllers;

class MinimalPd final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override {
    return {{.name = "target", .unit = "rad", .size = kPerJoint},
            {.name = "kp", .unit = "N m/rad", .default_value = {100.0}, .min = 0.0},
            {.name = "kd", .unit = "N m s/rad", .default_value = {10.0}, .min = 0.0}};
  }
  void configure(WholeBodyInterface& robot, const ParameterTable& parameters) override {
    robot_ = &robot;
    state_ = RobotState(robot.dofs());
    g_.setZero(robot.dofs() + 6);
    tau_.setZero(robot.dofs());
    parameters_changed(parameters);
  }
  void parameters_changed(const ParameterTable& p) override {  // between two ticks
    q_d_ = Eigen::Map<const Eigen::VectorXd>(p.values(0).data(), robot_->dofs());
    kp_ = p.value(1), kd_ = p.value(2);
  }
  void activate(const RobotState&) override { robot_->set_control_mode(ControlMode::torque); }
  bool update(double /*time_s*/, double /*period_s*/) override {  // no allocation
    robot_->state().read_robot_state(state_, ReadMode::latest);
    robot_->model().gravity_forces(state_.q, state_.world_H_base, {0, 0, -9.81}, g_);
    tau_ = g_.tail(robot_->dofs()) - kp_ * (state_.q - q_d_) - kd_ * state_.dq;
    return true;  // the host sends tau_
  }
  const Eigen::VectorXd& command() const override { return tau_; }
  std::string summary() const override {  // printed when the host stops
    char line[64];
    std::snprintf(line, sizeof line, "minimal_pd: max joint error %.4f rad",
                  (state_.q - q_d_).cwiseAbs().maxCoeff());
    return line;
  }

 private:
  WholeBodyInterface* robot_ = nullptr;
  RobotState state_;
  Eigen::VectorXd q_d_, g_, tau_;
  double kp_ = 0.0, kd_ = 0.0;
};
}  // namespace example

WBI_PLUGIN(catalog) {
  catalog.registry<wbi::controllers::ControllerRegistry>().add<example::MinimalPd>(
      "minimal_pd", "PD + gravity towards a target (controllers/README.md's example)");
}
