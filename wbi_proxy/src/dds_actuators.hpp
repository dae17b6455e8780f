// The Actuators element: publishes wbi/<robot>/commands (modes and references
// of all controlled joints, robot joint indices resolved once at init) and
// wbi/<robot>/control_parameters (values left as they are travel as NaN).
// It holds the joint claim (joint_claim.hpp): claimed at init before any
// command, checked before each, released at close.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <wbi/dds/publisher.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "joint_claim.hpp"
#include "robot_connection.hpp"
#include "wbi/actuators.hpp"

namespace wbi::proxy {

class DdsActuators final : public wbi::Actuators {
 public:
  explicit DdsActuators(RobotConnection& robot);

  // Waits up to `deadline` for the actuator component to read the commands;
  // appends it to `missing` when it does not.
  void wait(std::chrono::steady_clock::time_point deadline, std::vector<std::string>& missing);
  // Sizes the messages for the controlled joints (after RobotConnection::resolve).
  void prepare();
  // Claims the controlled joints as the options say (DdsInterfaceOptions::claim):
  // a wbi::Error names each joint another controller holds.
  void claim(std::chrono::nanoseconds timeout);
  void release() { claim_.reset(); }

  void set_control_mode(ControlMode mode) override;
  void set_control_mode(ControlMode mode, int joint) override;
  void set_control_reference(const ConstVectorRef& reference) override;
  void set_control_reference(double reference, int joint) override;
  void set_control_parameter(ControlParameter parameter, const ConstVectorRef& values) override;
  void set_control_parameter(ControlParameter parameter, double value, int joint) override;

 private:
  int dofs() const { return static_cast<int>(modes_.size()); }
  void switch_mode(int joint, ControlMode mode);
  // A joint's reference, where the command message holds it.
  double& reference_of(int joint) { return command_.references()[static_cast<std::size_t>(joint)]; }
  // answers: the command is a reference computed from the samples read (it
  // answers their tick), not a mode switch (it carries the last answer's tick).
  void publish_command(bool answers);
  std::vector<double>& parameter_values(ControlParameter parameter);
  void publish_parameters(ControlParameter parameter);

  RobotConnection& robot_;
  dds::Publisher<wbi::msg::ActuatorCommand> commands_;
  dds::Publisher<wbi::msg::ControlParameters> parameters_;
  std::vector<ControlMode> modes_;     // [dofs] current mode per controlled joint
  wbi::msg::ActuatorCommand command_;  // as it goes on the wire; its references the only copy
  wbi::msg::ControlParameters parameters_msg_;
  std::uint64_t command_seq_ = 0;
  // The tick the last reference answered and the stamp of its sample
  // (ActuatorCommand.tick and source_stamp_ns): msg::kNoTick and 0 until one did.
  std::uint64_t answered_tick_ = msg::kNoTick;
  std::int64_t answered_stamp_ns_ = 0;
  std::uint64_t parameters_seq_ = 0;
  std::unique_ptr<JointClaim> claim_;  // from claim() to release()
};

}  // namespace wbi::proxy
