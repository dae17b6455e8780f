// A robot peer for proxy and controller tests: the 7-joint arm as DDS sees it
// (description, sensor and state streams; command and parameter readers),
// made of real DDS endpoints in the test's process.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/dds_interface.hpp>

#include "test_support.hpp"

namespace wbi::test {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;

inline const std::vector<std::string> kArmJoints{"joint_1", "joint_2", "joint_3", "joint_4",
                                                 "joint_5", "joint_6", "joint_7"};

// Robot r's joint j position in the peer's samples.
inline double arm_position(std::size_t j) { return 0.1 * static_cast<double>(j + 1); }
inline double arm_velocity(std::size_t j) { return -0.01 * static_cast<double>(j + 1); }
// F/T sensor i's vertical force [N] (and minus its torque about x [N·m]).
inline double arm_wrench(std::size_t i) { return 5.0 * static_cast<double>(i + 1); }
// With F/T sensors, the state also carries an external-wrench estimate on this
// link: this vertical force [N], and minus it as moment about y [N·m].
inline const char* const kArmWrenchLink = "ee_link";
inline constexpr double kArmExternalForce = 7.5;

// The robot side, as DDS sees it: description, sensor and state streams, a
// command and a parameter reader. Streams are published at 200 Hz while running.
class ArmPeer {
 public:
  // force_torque_sensors: F/T sensors "ft_0", … in the description, their readings
  // in the sensor samples (arm_wrench), and, unless state_without_force_torque, the
  // same in the state estimates. lockstep: the description says so, and the
  // peer publishes tick 0 only, as a lockstep robot waiting for its answer.
  explicit ArmPeer(const std::string& robot, int force_torque_sensors = 0,
                   bool state_without_force_torque = false, bool lockstep = false)
      : participant_("robot"),
        description_(participant_, topics::description(robot), qos::kLatched),
        sensors_(participant_, topics::sensors(robot), qos::kStream),
        state_(participant_, topics::state(robot), qos::kStream),
        commands_(participant_, topics::commands(robot), qos::kCommand),
        parameters_(participant_, topics::control_parameters(robot), qos::kCommand),
        robot_(robot),
        force_torque_sensors_(static_cast<std::size_t>(force_torque_sensors)),
        state_without_force_torque_(state_without_force_torque),
        lockstep_(lockstep) {
    wbi::msg::RobotDescription description;
    description.header().robot(robot);
    description.lockstep(lockstep);
    for (const auto& joint : kArmJoints) {
      description.joint_names().push_back(joint);
    }
    for (std::size_t i = 0; i < force_torque_sensors_; ++i) {
      wbi::msg::SensorInfo sensor;
      sensor.name("ft_" + std::to_string(i));
      sensor.kind(wbi::msg::SensorKind::FORCE_TORQUE);
      description.sensors().push_back(sensor);
    }
    description_.publish(description);
    thread_ = std::thread([this] { run(); });
  }

  ~ArmPeer() { stop(); }

  void stop() {
    running_ = false;
    if (thread_.joinable()) {
      thread_.join();
    }
  }

  // The number of the last sample published (valid once stop() returned): a
  // reader that has it has everything the peer sent.
  std::uint64_t last_published_seq() const { return last_published_seq_; }
  // Readers of its sensor samples (a proxy subscribes when something reads them).
  const wbi::dds::Publisher<wbi::msg::SensorSample>& sensor_writer() const { return sensors_; }

  wbi::dds::Subscriber<wbi::msg::ActuatorCommand>& commands() { return commands_; }
  wbi::dds::Subscriber<wbi::msg::ControlParameters>& parameters() { return parameters_; }

 private:
  void run() {
    wbi::msg::SensorSample sample;
    wbi::msg::StateEstimate state;
    sample.header().robot(robot_);
    state.header().robot(robot_);
    for (std::size_t j = 0; j < kArmJoints.size(); ++j) {
      sample.encoder_position().push_back(arm_position(j));
      state.q().push_back(arm_position(j));
      state.dq().push_back(arm_velocity(j));
      state.ddq().push_back(0.0);
      state.tau().push_back(0.0);
    }
    for (std::size_t i = 0; i < force_torque_sensors_; ++i) {
      wbi::msg::ForceTorqueReading reading;
      auto& w = reading.wrench();
      w.force().z(arm_wrench(i));
      w.torque().x(-arm_wrench(i));
      sample.force_torque().push_back(reading);
      if (!state_without_force_torque_) {
        state.force_torque().push_back(w);
      }
    }
    if (force_torque_sensors_ > 0) {
      wbi::msg::ExternalWrenchEstimate external;
      external.link(kArmWrenchLink);
      external.wrench().force().z(kArmExternalForce);
      external.wrench().torque().y(-kArmExternalForce);
      external.contact(true);
      external.valid(true);
      state.external_wrenches().push_back(external);
    }
    state.base_pose().orientation().w(1.0);
    state.base_pose().position().z(0.25);
    for (std::uint64_t seq = 0; running_; ++seq) {
      sample.header().seq(seq);
      sample.header().stamp_ns(static_cast<std::int64_t>(seq) * 5'000'000);
      state.header() = sample.header();
      // Fields no test expects constant carry the sample's number: a read that
      // mixed two samples would show it (read_robot_state).
      std::fill(state.ddq().begin(), state.ddq().end(), static_cast<double>(seq));
      state.base_velocity()[0] = static_cast<double>(seq);
      state.base_pose().position().x(static_cast<double>(seq));
      sensors_.publish(sample);
      state_.publish(state);
      last_published_seq_ = seq;
      if (lockstep_) {
        return;  // tick 0 stays unanswered: nothing newer comes
      }
      std::this_thread::sleep_for(5ms);  // the robot's rate, not a synchronisation
    }
  }

  wbi::dds::Participant participant_;
  wbi::dds::Publisher<wbi::msg::RobotDescription> description_;
  wbi::dds::Publisher<wbi::msg::SensorSample> sensors_;
  wbi::dds::Publisher<wbi::msg::StateEstimate> state_;
  wbi::dds::Subscriber<wbi::msg::ActuatorCommand> commands_;
  wbi::dds::Subscriber<wbi::msg::ControlParameters> parameters_;
  std::string robot_;
  std::size_t force_torque_sensors_;
  bool state_without_force_torque_;
  std::atomic<bool> running_{true};
  bool lockstep_ = false;
  std::atomic<std::uint64_t> last_published_seq_{0};
  std::thread thread_;
};

inline wbi::DdsInterfaceOptions arm_options(const std::string& robot) {
  wbi::DdsInterfaceOptions options;
  options.robot = robot;
  options.controller = "test_controller";
  options.urdf = wbi::test::project_model("arm7.urdf").string();
  options.max_age_s = 0.5;
  // The peer is the robot's streams only: it answers no joint claims (the
  // robot's claims are tested on the robot: test_joint_claims, test_rogue_producer).
  options.claim = wbi::DdsInterfaceOptions::Claim::none;
  return options;
}

}  // namespace wbi::test
