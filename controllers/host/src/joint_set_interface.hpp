// What a hosted controller sees of the host's whole-body interface: all of it
// (every joint's state, the whole model), but its Actuators reach only the
// joints it commands, and, in a host with chains, its State gives the state
// the tick began with (read once by the host: a planner and the controller it
// feeds answer the same estimate, whatever arrives meanwhile). Several controllers active on
// disjoint joint sets thus each set their own joints' control mode in activate(), as a controller
// run alone does, and never another's. References are the host's to send (command()); a controller
// that sends them itself is told so.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <wbi/whole_body_interface.hpp>

namespace wbi::controllers {

// The state a tick began with, when the host pinned one (valid).
struct PinnedState {
  RobotState state;
  bool valid = false;
};

class JointSetInterface final : public WholeBodyInterface {
 public:
  // joints: indices into robot.joint_list(). pinned: the host's, alive as long as this.
  JointSetInterface(WholeBodyInterface& robot, std::string controller, std::vector<int> joints,
                    const PinnedState& pinned)
      : robot_(robot),
        actuators_(robot, std::move(controller), std::move(joints)),
        state_(robot, pinned) {}

  void add_joints(const IdList& /*joints*/) override {
    throw Error("controller '" + actuators_.controller + "': the host chose the joints");
  }
  void init(std::chrono::milliseconds /*timeout*/) override {}  // the host's is initialised
  void close() override {}                                      // and closed by the host
  const IdList& joint_list() const override { return robot_.joint_list(); }
  Actuators& actuators() override { return actuators_; }
  Sensors& sensors() override { return robot_.sensors(); }
  State& state() override { return state_; }
  Model& model() override { return robot_.model(); }
  const Model& model() const override { return std::as_const(robot_).model(); }
  const Sensors& sensors() const override { return std::as_const(robot_).sensors(); }
  const State& state() const override { return state_; }

 private:
  struct JointSetActuators final : Actuators {
    JointSetActuators(WholeBodyInterface& host, std::string name, std::vector<int> commanded)
        : robot(host), controller(std::move(name)), joints(std::move(commanded)) {}

    // Every joint it commands; all at once (one robot tick) when it commands them all.
    void set_control_mode(ControlMode mode) override {
      if (static_cast<int>(joints.size()) == robot.dofs()) {
        robot.actuators().set_control_mode(mode);
        return;
      }
      for (const int joint : joints) {
        robot.actuators().set_control_mode(mode, joint);
      }
    }
    void set_control_mode(ControlMode mode, int joint) override {
      check(joint);
      robot.actuators().set_control_mode(mode, joint);
    }
    void set_control_reference(const ConstVectorRef& /*reference*/) override { refuse(); }
    void set_control_reference(double /*reference*/, int /*joint*/) override { refuse(); }
    void set_control_parameter(ControlParameter parameter, const ConstVectorRef& values) override {
      for (const int joint : joints) {
        robot.actuators().set_control_parameter(parameter, values[joint], joint);
      }
    }
    void set_control_parameter(ControlParameter parameter, double value, int joint) override {
      check(joint);
      robot.actuators().set_control_parameter(parameter, value, joint);
    }

    void check(int joint) const {
      for (const int own : joints) {
        if (own == joint) {
          return;
        }
      }
      throw Error("controller '" + controller + "' does not command joint " +
                  (joint >= 0 && joint < robot.dofs()
                       ? "'" + robot.joint_list()[static_cast<std::size_t>(joint)] + "'"
                       : std::to_string(joint)));
    }
    [[noreturn]] void refuse() const {
      throw Error("controller '" + controller +
                  "': the host sends its command(); hosted controllers do not send references");
    }

    WholeBodyInterface& robot;
    const std::string controller;
    const std::vector<int> joints;
  };

  // read_robot_state and read_base_pose (latest) give the pinned state while
  // there is one; everything else is the host's State.
  struct TickState final : State {
    TickState(WholeBodyInterface& host, const PinnedState& tick) : robot(host), pinned(tick) {}
    Stamp read_estimates(EstimateKind kind, VectorRef values, ReadMode mode) override {
      return robot.state().read_estimates(kind, values, mode);
    }
    Stamp read_estimate(EstimateKind kind, int index, VectorRef values, ReadMode mode) override {
      return robot.state().read_estimate(kind, index, values, mode);
    }
    Stamp read_robot_state(RobotState& out, ReadMode mode) override {
      if (pinned.valid && mode == ReadMode::latest) {
        out = pinned.state;  // same sizes: no allocation
        return out.stamp;
      }
      return robot.state().read_robot_state(out, mode);
    }
    const IdList& external_wrench_links() const override {
      return std::as_const(robot).state().external_wrench_links();
    }
    Stamp read_base_pose(Transform& world_H_base, ReadMode mode) override {
      if (pinned.valid && mode == ReadMode::latest) {
        world_H_base = pinned.state.world_H_base;
        return pinned.state.stamp;
      }
      return robot.state().read_base_pose(world_H_base, mode);
    }
    void set_estimation_parameter(const std::string& name, double value) override {
      robot.state().set_estimation_parameter(name, value);
    }

    WholeBodyInterface& robot;
    const PinnedState& pinned;
  };

  WholeBodyInterface& robot_;
  JointSetActuators actuators_;
  TickState state_;
};

}  // namespace wbi::controllers
