// Writes a small wbi recording with known values, for test_python_recording:
//   wbi_test_write_recording FILE.mcap none|zstd|lz4
// Messages are real wbi IDL samples serialized by their Fast DDS type support
// (exactly what DDS carries and `wbi record` stores), with omgidl schemas from
// idl_text_for. The values follow formulas that tests/python/test_recording.py
// repeats, per message index k:
//   wbi/arm/state (StateEstimate), k = 0..49, log time 1e9 + k·1e6 ns, publish time +10:
//     header {robot "arm", stamp_ns 1e6·k, seq k}; q[j] = 0.1·k + j (7 joints);
//     dq[j] = −0.01·k·(j+1); ddq empty; tau = [k] when k is even, else empty;
//     base_pose {position (0.5k, k, 1.5k), orientation (1, 0, 0, 0)};
//     base_velocity[i] = k + i/10; base_acceleration[i] = −i;
//     force_torque: 2 wrenches, force.x = k + w, torque.z = −k − w; warnings = k mod 3
//   wbi/arm/commands (ActuatorCommand), k = 0..19, log time 1e9 + 2k·1e6 + 5e5 ns:
//     controller "pd", tick k, source_stamp_ns −k, joints 0..6, modes POSITION for
//     joint 0 and TORQUE for the rest, references[j] = k + 0.5·j
//   wbi/arm/status (ComponentStatus), k = 0..2, log time 1e9 + 20k·1e6 ns:
//     instance "arm", type "sim_robot", state ACTIVE, rate_hz 1000, iterations 1000k,
//     last_error "" (k < 2) or "boom", counters [{"rejected", k}, {"late", 2k}]
//   wbi/arm/sensors (SensorSample), k = 0..9, log time 1e9 + 5k·1e6 + 1 ns:
//     encoder_position[j] = j − k, imus: one, orientation (1, 0, 0, 0),
//     angular_velocity (k, 0, 0), linear_acceleration (0, 0, 9.81)
//   wbi/arm/description (RobotDescription), one at log time 1e9 ns: joint_names
//     joint_1 … joint_7
//   wbi/arm/signals/pd (Signals), k = 0..4, log time 1e9 + 10k·1e6 + 2 ns: source "pd",
//     names (error, effort), values (k, −2k)
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>
#include <wbi/dds/message_traits.hpp>
#include <wbi/mcap/writer.hpp>
#include <wbi/msg/idl_text.hpp>

namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

constexpr std::uint64_t kStart = 1'000'000'000;
constexpr std::uint64_t kMs = 1'000'000;

// One topic of the recording: its channel and the serialization of its type.
template <class T>
class Topic {
 public:
  Topic(wbi::mcap::Writer& writer, const std::string& name) : writer_(writer) {
    const char* type = wbi::dds::MessageTraits<T>::kName;
    channel_ = writer.add_channel(writer.add_schema(type, wbi::msg::idl_text_for(type)), name);
  }

  void write(T sample, std::uint32_t sequence, std::uint64_t log_time) {
    payload_.reserve(type_.getSerializedSizeProvider(&sample)());
    if (!type_.serialize(&sample, &payload_)) {
      throw std::runtime_error("serialization failed");
    }
    writer_.write(channel_, sequence, log_time, log_time + 10, {payload_.data, payload_.length});
  }

 private:
  wbi::mcap::Writer& writer_;
  typename wbi::dds::MessageTraits<T>::TypeSupport type_;
  SerializedPayload_t payload_;
  std::uint16_t channel_ = 0;
};

wbi::msg::Header header(std::uint64_t k) {
  wbi::msg::Header h;
  h.robot("arm");
  h.stamp_ns(static_cast<std::int64_t>(k * kMs));
  h.seq(k);
  return h;
}

wbi::msg::StateEstimate state(std::uint64_t k) {
  const double x = static_cast<double>(k);
  wbi::msg::StateEstimate s;
  s.header(header(k));
  for (int j = 0; j < 7; ++j) {
    s.q().push_back(0.1 * x + j);
    s.dq().push_back(-0.01 * x * (j + 1));
  }
  if (k % 2 == 0) {
    s.tau().push_back(x);
  }
  s.base_pose().position().x(0.5 * x);
  s.base_pose().position().y(x);
  s.base_pose().position().z(1.5 * x);
  s.base_pose().orientation().w(1.0);
  for (int i = 0; i < 6; ++i) {
    s.base_velocity()[i] = x + i / 10.0;
    s.base_acceleration()[i] = -i;
  }
  for (int w = 0; w < 2; ++w) {
    wbi::msg::Wrench wrench;
    wrench.force().x(x + w);
    wrench.torque().z(-x - w);
    s.force_torque().push_back(wrench);
  }
  s.warnings(static_cast<std::uint32_t>(k % 3));
  return s;
}

wbi::msg::ActuatorCommand command(std::uint64_t k) {
  wbi::msg::ActuatorCommand c;
  c.header(header(k));
  c.controller("pd");
  c.tick(k);
  c.source_stamp_ns(-static_cast<std::int64_t>(k));
  for (std::uint16_t j = 0; j < 7; ++j) {
    c.joints().push_back(j);
    c.modes().push_back(j == 0 ? wbi::msg::ControlMode::POSITION : wbi::msg::ControlMode::TORQUE);
    c.references().push_back(static_cast<double>(k) + 0.5 * j);
  }
  return c;
}

wbi::msg::ComponentStatus status(std::uint64_t k) {
  wbi::msg::ComponentStatus s;
  s.header(header(k));
  s.instance("arm");
  s.type("sim_robot");
  s.state(wbi::msg::LifecycleState::ACTIVE);
  s.rate_hz(1000.0);
  s.iterations(1000 * k);
  s.last_error(k < 2 ? "" : "boom");
  wbi::msg::Counter rejected;
  rejected.name("rejected");
  rejected.value(k);
  wbi::msg::Counter late;
  late.name("late");
  late.value(2 * k);
  s.counters({rejected, late});
  return s;
}

wbi::msg::SensorSample sensors(std::uint64_t k) {
  wbi::msg::SensorSample s;
  s.header(header(k));
  for (int j = 0; j < 7; ++j) {
    s.encoder_position().push_back(j - static_cast<double>(k));
  }
  wbi::msg::ImuReading imu;
  imu.orientation().w(1.0);
  imu.angular_velocity().x(static_cast<double>(k));
  imu.linear_acceleration().z(9.81);
  s.imus().push_back(imu);
  return s;
}

wbi::msg::RobotDescription description() {
  wbi::msg::RobotDescription d;
  d.header(header(0));
  for (int j = 1; j <= 7; ++j) {
    d.joint_names().emplace_back("joint_" + std::to_string(j));
  }
  return d;
}

wbi::msg::Signals signals(std::uint64_t k) {
  wbi::msg::Signals s;
  s.header(header(k));
  s.source("pd");
  s.names().emplace_back("error");
  s.names().emplace_back("effort");
  s.values({static_cast<double>(k), -2.0 * static_cast<double>(k)});
  return s;
}

wbi::mcap::Compression compression_from(const std::string& name) {
  if (name == "none") {
    return wbi::mcap::Compression::none;
  }
  if (name == "zstd") {
    return wbi::mcap::Compression::zstd;
  }
  if (name == "lz4") {
    return wbi::mcap::Compression::lz4;
  }
  throw std::invalid_argument("compression is '" + name + "'; expected none, zstd or lz4");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: wbi_test_write_recording FILE.mcap none|zstd|lz4\n");
    return 2;
  }
  try {
    wbi::mcap::WriterOptions options;
    options.compression = compression_from(argv[2]);
    options.chunk_size = 4096;  // several chunks, so that log-time order crosses chunks
    wbi::mcap::Writer writer(argv[1], options);
    Topic<wbi::msg::StateEstimate> state_topic(writer, "wbi/arm/state");
    Topic<wbi::msg::ActuatorCommand> command_topic(writer, "wbi/arm/commands");
    Topic<wbi::msg::ComponentStatus> status_topic(writer, "wbi/arm/status");
    Topic<wbi::msg::SensorSample> sensor_topic(writer, "wbi/arm/sensors");
    Topic<wbi::msg::RobotDescription> description_topic(writer, "wbi/arm/description");
    Topic<wbi::msg::Signals> signals_topic(writer, "wbi/arm/signals/pd");
    description_topic.write(description(), 0, kStart);
    for (std::uint64_t k = 0; k < 50; ++k) {
      const auto kk = static_cast<std::uint32_t>(k);
      state_topic.write(state(k), kk, kStart + k * kMs);
      if (k < 20) {
        command_topic.write(command(k), kk, kStart + 2 * k * kMs + kMs / 2);
      }
      if (k < 3) {
        status_topic.write(status(k), kk, kStart + 20 * k * kMs);
      }
      if (k < 10) {
        sensor_topic.write(sensors(k), kk, kStart + 5 * k * kMs + 1);
      }
      if (k < 5) {
        signals_topic.write(signals(k), kk, kStart + 10 * k * kMs + 2);
      }
    }
    writer.close();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wbi_test_write_recording: %s\n", error.what());
    return 1;
  }
  return 0;
}
