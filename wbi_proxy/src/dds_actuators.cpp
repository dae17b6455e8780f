#include "dds_actuators.hpp"

#include <algorithm>
#include <limits>

#include <wbi/msg/eigen.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "size_check.hpp"

namespace wbi::proxy {

namespace {

constexpr double kUnchanged = std::numeric_limits<double>::quiet_NaN();

}  // namespace

DdsActuators::DdsActuators(RobotConnection& robot)
    : robot_(robot),
      commands_(robot.participant, dds::topics::commands(robot.options.robot), dds::qos::kCommand),
      parameters_(robot.participant, dds::topics::control_parameters(robot.options.robot),
                  dds::qos::kCommand) {}

void DdsActuators::wait(std::chrono::steady_clock::time_point deadline,
                        std::vector<std::string>& missing) {
  const auto remaining = std::max(std::chrono::steady_clock::duration::zero(),
                                  deadline - std::chrono::steady_clock::now());
  // The robot's own reader, not any (the estimator reads the commands too): a
  // first command written before it matched would not reach the robot, which
  // in lockstep waits for it at tick 0 (with DDS Security the pairs match
  // seconds apart). The robot is the participant that sent the description.
  const dds::detail::Guid robot = robot_.description.producers().bound;
  const bool matched = robot != dds::detail::Guid{}
                           ? commands_.wait_for_subscriber_of(robot, remaining)
                           : commands_.wait_for_subscribers(1, remaining);
  if (!matched) {
    missing.push_back("the robot's reader of " + dds::topics::commands(robot_.options.robot) +
                      " (actuator component)");
  }
}

void DdsActuators::prepare() {
  const auto n = robot_.controlled.size();
  const auto& options = robot_.options;
  modes_.assign(n, ControlMode::idle);
  command_.header().robot(options.robot);
  command_.controller(options.controller);
  command_.joints(robot_.robot_index);
  command_.modes().assign(n, wbi::msg::ControlMode::IDLE);
  command_.references().assign(n, 0.0);
  answered_tick_ = msg::kNoTick;
  answered_stamp_ns_ = 0;
  parameters_msg_.header().robot(options.robot);
  parameters_msg_.controller(options.controller);
  parameters_msg_.joints(robot_.robot_index);
  for (auto* values : {&parameters_msg_.kp(), &parameters_msg_.ki(), &parameters_msg_.kd(),
                       &parameters_msg_.reference_speed()}) {
    values->assign(n, kUnchanged);
  }
}

void DdsActuators::claim(std::chrono::nanoseconds timeout) {
  const auto& options = robot_.options;
  if (options.claim == DdsInterfaceOptions::Claim::none) {
    return;
  }
  claim_ = std::make_unique<JointClaim>(
      robot_.participant, options.robot, options.controller, robot_.controlled,
      std::vector<int>(robot_.robot_index.begin(), robot_.robot_index.end()));
  claim_->claim(timeout, options.claim == DdsInterfaceOptions::Claim::force);
}

void DdsActuators::set_control_mode(ControlMode mode) {
  robot_.require_init();
  for (int k = 0; k < dofs(); ++k) {
    switch_mode(k, mode);
  }
  publish_command(false);
}

void DdsActuators::set_control_mode(ControlMode mode, int joint) {
  robot_.require_init();
  check_index("joint", joint, dofs());
  switch_mode(joint, mode);
  publish_command(false);
}

void DdsActuators::set_control_reference(const ConstVectorRef& reference) {
  robot_.require_init();
  check_size("control reference", reference.size(), dofs());
  msg::to_wire(reference, command_.references());  // held in the message: the one copy
  publish_command(true);
}

void DdsActuators::set_control_reference(double reference, int joint) {
  robot_.require_init();
  check_index("joint", joint, dofs());
  reference_of(joint) = reference;
  publish_command(true);
}

void DdsActuators::set_control_parameter(ControlParameter parameter, const ConstVectorRef& values) {
  robot_.require_init();
  check_size("control parameter values", values.size(), dofs());
  auto& out = parameter_values(parameter);
  for (int k = 0; k < dofs(); ++k) {
    out[static_cast<std::size_t>(k)] = values[k];
  }
  publish_parameters(parameter);
}

void DdsActuators::set_control_parameter(ControlParameter parameter, double value, int joint) {
  robot_.require_init();
  check_index("joint", joint, dofs());
  auto& values = parameter_values(parameter);
  std::fill(values.begin(), values.end(), kUnchanged);  // NaN: leave this joint as it is
  values[static_cast<std::size_t>(joint)] = value;
  publish_parameters(parameter);
}

// A position mode starts at the measured position (the newest state's q, the
// encoders' reading), the others at zero.
void DdsActuators::switch_mode(int joint, ControlMode mode) {
  modes_[static_cast<std::size_t>(joint)] = mode;
  if (mode == ControlMode::position || mode == ControlMode::position_direct) {
    robot_.state.read(
        kModeSwitchRead, ReadMode::latest, robot_.options.max_age_s,
        robot_.options.blocking_read_timeout, [&](const wbi::msg::StateEstimate& state) {
          reference_of(joint) = state.q().at(robot_.robot_index[static_cast<std::size_t>(joint)]);
        });
  } else {
    reference_of(joint) = 0.0;
  }
}

void DdsActuators::publish_command(bool answers) {
  if (claim_) {
    claim_->check();  // throws once another controller took a joint
  }
  // Lockstep: a reference answers the tick of the newest sample the controller
  // read (sensor and state samples carry the robot's tick as their sequence
  // number), once it read one. A mode switch, or a reference sent before any
  // read, answers nothing: it carries the last answer's tick (kNoTick before the
  // first). Else the start-up mode switch, sent with tick 0 before any sample,
  // could answer tick 0, and the robot would step it with zero torque or with
  // the first computed command depending on timing.
  const auto& state = robot_.state.last;
  const std::uint64_t sensors_read = robot_.sensors ? robot_.sensors->last.count : 0;
  if (answers && (sensors_read > 0 || state.count > 0)) {
    robot_.state.answered();
    if (robot_.sensors) {
      robot_.sensors->answered();
    }
    answered_tick_ = state.seq;
    // Latency: the sensor sample this command was computed from (a state
    // estimate carries its sensor sample's stamp).
    answered_stamp_ns_ = state.stamp_ns;
    if (sensors_read > 0) {
      const auto& sensors = robot_.sensors->last;
      answered_tick_ = std::max(answered_tick_, sensors.seq);
      answered_stamp_ns_ = std::max(answered_stamp_ns_, sensors.stamp_ns);
    }
  }
  auto& header = command_.header();
  header.stamp_ns(system_now_ns());
  header.seq(command_seq_++);
  command_.tick(answered_tick_);
  command_.source_stamp_ns(answered_stamp_ns_);
  for (std::size_t k = 0; k < modes_.size(); ++k) {
    command_.modes()[k] = msg::to_wire(modes_[k]);
  }
  if (!commands_.publish(command_)) {
    throw Error("command to robot '" + robot_.options.robot + "' not sent");
  }
}

std::vector<double>& DdsActuators::parameter_values(ControlParameter parameter) {
  switch (parameter) {
    case ControlParameter::kp:
      return parameters_msg_.kp();
    case ControlParameter::ki:
      return parameters_msg_.ki();
    case ControlParameter::kd:
      return parameters_msg_.kd();
    case ControlParameter::reference_speed:
      return parameters_msg_.reference_speed();
  }
  throw Error("unknown control parameter");
}

// Publishes one parameter; the others travel as NaN (unchanged).
void DdsActuators::publish_parameters(ControlParameter parameter) {
  if (claim_) {
    claim_->check();
  }
  for (auto other : {ControlParameter::kp, ControlParameter::ki, ControlParameter::kd,
                     ControlParameter::reference_speed}) {
    if (other != parameter) {
      auto& values = parameter_values(other);
      std::fill(values.begin(), values.end(), kUnchanged);
    }
  }
  parameters_msg_.header().stamp_ns(system_now_ns());
  parameters_msg_.header().seq(parameters_seq_++);
  if (!parameters_.publish(parameters_msg_)) {
    throw Error("control parameters for robot '" + robot_.options.robot + "' not sent");
  }
}

}  // namespace wbi::proxy
