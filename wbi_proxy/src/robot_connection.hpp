// What every DDS element of one interface shares: the participant, the
// robot's description, its state stream, its sensor stream once something
// reads it (DdsInterfaceOptions::read_sensors), and the controlled joints
// resolved against the robot's order.
//
// Orders: the controller's joint list C (add_joints) is the order of every
// joint vector of the interface. The robot's order R comes from its
// description; robot_index[k] is the position in R of controlled joint k,
// resolved once in resolve(). The elements gather robot-order vectors into C.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "stream.hpp"
#include "wbi/dds_interface_options.hpp"

namespace wbi::proxy {

// Kinds of read that keep their own "seen" count for blocking reads.
constexpr std::size_t kSensorReads = enum_count<SensorKind>();
constexpr std::size_t kStateReads = 11;  // EstimateKind, read_robot_state, a mode switch
constexpr std::size_t kRobotStateRead = 9;
constexpr std::size_t kModeSwitchRead = 10;  // the measured position a position mode starts at

std::int64_t system_now_ns();

class RobotConnection {
 public:
  explicit RobotConnection(const DdsInterfaceOptions& options);

  // Waits up to `deadline` for the description, a state estimate and, when
  // subscribed (read_sensors), a sensor sample; appends what is missing to `missing`.
  void wait(std::chrono::steady_clock::time_point deadline, std::vector<std::string>& missing);
  // The sensor stream, subscribed to by the first call, which then waits up to
  // blocking_read_timeout for its first sample (the stream is transient-local:
  // a new reader gets the newest sample at once when there is one).
  Stream<wbi::msg::SensorSample, kSensorReads>& sensor_stream();
  // Resolves the controlled joints and the sensor names against the description
  // (after wait()); throws Error naming a joint the robot does not have.
  void resolve(const IdList& controlled);
  // Joints of the robot outside the controlled list: from the options, else
  // where the state estimate init() saw puts them (its q: the encoders').
  std::map<std::string, double> locked_positions() const;

  // Joint values in robot order → controlled joints [first, first + count).
  void gather(const std::vector<double>& robot_values, int first, int count, VectorRef out,
              const char* what) const;

  // Throws Error naming the controlled joints in [first, first + count) that
  // have no joint-torque sensor (`torques`: a sample's joint_torque, empty
  // when the robot has none); nothing when all have one. Never allocates then.
  void require_torque_sensors(const std::vector<double>& torques, int first, int count) const;

  void require_init() const;
  // The robot steps only once its controllers answered each tick (its description says so).
  bool lockstep() const { return description_rx.count > 0 && description_rx.sample.lockstep(); }

  const DdsInterfaceOptions options;
  std::optional<dds::Participant> own_participant;  // unless options.shared_participant
  dds::Participant& participant;
  dds::Subscriber<wbi::msg::RobotDescription> description;
  dds::Received<wbi::msg::RobotDescription> description_rx;
  Stream<wbi::msg::StateEstimate, kStateReads> state;
  std::unique_ptr<Stream<wbi::msg::SensorSample, kSensorReads>> sensors;  // once read

  IdList controlled;                       // C, from add_joints
  std::vector<std::uint16_t> robot_index;  // [dofs] position of controlled joint k in R
  IdList imu_names;
  IdList force_torque_names;
  IdList external_wrench_links;         // of the state estimate init() saw
  std::vector<double> first_positions;  // [robot joints] R order: q of the state init() saw
  std::vector<bool> torque_sensor;      // [robot joints] R order: has a joint-torque sensor
  bool initialized = false;

 private:
  void subscribe_sensors();
};

}  // namespace wbi::proxy
