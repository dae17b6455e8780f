// What a hosted controller sees of the host's whole-body interface: all of it
// (every joint's state, the whole model), but its Actuators reach only the
// joints it commands. Several controllers active on disjoint joint sets thus
// each set their own joints' control mode in activate(), as a controller run
// alone does, and never another's. References are the host's to send
// (command()); a controller that sends them itself is told so.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <wbi/whole_body_interface.hpp>

namespace wbi::controllers {

class JointSetInterface final : public WholeBodyInterface {
 public:
  // joints: indices into robot.joint_list(); all of them when `all`.
  JointSetInterface(WholeBodyInterface& robot, std::string controller, std::vector<int> joints)
      : robot_(robot), actuators_(robot, std::move(controller), std::move(joints)) {}

  void add_joints(const IdList& /*joints*/) override {
    throw Error("controller '" + actuators_.controller + "': the host chose the joints");
  }
  void init(std::chrono::milliseconds /*timeout*/) override {}  // the host's is initialised
  void close() override {}                                      // and closed by the host
  const IdList& joint_list() const override { return robot_.joint_list(); }
  Actuators& actuators() override { return actuators_; }
  Sensors& sensors() override { return robot_.sensors(); }
  State& state() override { return robot_.state(); }
  Model& model() override { return robot_.model(); }
  const Model& model() const override { return std::as_const(robot_).model(); }
  const Sensors& sensors() const override { return std::as_const(robot_).sensors(); }
  const State& state() const override { return std::as_const(robot_).state(); }

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

  WholeBodyInterface& robot_;
  JointSetActuators actuators_;
};

}  // namespace wbi::controllers
