// Sensor-to-command latency seen by a third participant: it subscribes to the
// robot's sensor samples and to the commands sent to it. A command names the
// sensor sample it was computed from (ActuatorCommand.source_stamp_ns = that
// sample's Header.stamp_ns); its latency is the command's arrival here minus
// the sensor sample's DDS source timestamp (set when the robot wrote it).
// Both are system-clock times of one machine, so the latency is on one clock
// although the robot stamps its samples with simulation time.
#pragma once

#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

#include <wbi/msg/commands.h>
#include <wbi/msg/sensors.h>
#include <wbi/msg/state.h>
#include <wbi/msg/status.h>
#include <wbi/dds/subscriber.hpp>

namespace wbi::bench {

class LatencyObserver {
 public:
  // Keeps up to max_samples latencies (preallocated).
  LatencyObserver(dds::Participant& participant, const std::string& robot,
                  const std::string& controller_instance, std::size_t max_samples);

  struct Result {
    std::vector<double> latencies_us;  // one per command matched to its sensor sample
    // The same commands' latency split in three, by the writers' DDS source
    // timestamps: robot write -> estimator write (hop + estimate), estimator
    // write -> controller write (hop + control cycle with its model calls),
    // controller write -> arrival here (the command's delivery).
    std::vector<double> to_state_us, to_command_us, delivery_us;
    std::uint64_t sensor_samples = 0;
    std::uint64_t commands = 0;
    std::uint64_t unmatched_commands = 0;  // their sensor sample was not seen (or too old)
    std::uint64_t ticks = 0;               // controller loop iterations (its status)
    std::uint64_t overruns = 0;            // controller deadline misses (its status)
    std::int64_t status_stamp_ns = 0;      // stamp of the status that gave ticks and overruns
  };
  // The controller's loop rate [Hz] between two results, from its status reports
  // (ticks over the time between the reports, not over the observer's window:
  // reports come at the status period, and best effort may lose one). 0 when
  // no report came in between.
  static double loop_rate_hz(const Result& before, const Result& after);
  Result result() const;

 private:
  void on_sensor(const msg::SensorSample& sample, const dds::detail::SampleInfo& info);
  void on_state(const msg::StateEstimate& state, const dds::detail::SampleInfo& info);
  void on_command(const msg::ActuatorCommand& command, const dds::detail::SampleInfo& info);
  void on_status(const msg::ComponentStatus& status);

  struct Seen {
    std::int64_t stamp_ns = -1;           // Header.stamp_ns
    std::int64_t published_ns = 0;        // DDS source timestamp (system clock)
    std::int64_t state_published_ns = 0;  // its estimate's DDS source timestamp, 0: not seen
  };
  static constexpr std::size_t kSlots = 4096;  // sensor samples remembered (4 s at 1 kHz)

  std::string controller_instance_;
  mutable std::mutex mutex_;
  std::array<Seen, kSlots> seen_{};
  std::uint64_t sensor_count_ = 0;
  Result result_;
  std::size_t max_samples_;

  dds::Subscriber<msg::SensorSample> sensors_;
  dds::Subscriber<msg::StateEstimate> states_;
  dds::Subscriber<msg::ActuatorCommand> commands_;
  dds::Subscriber<msg::ComponentStatus> status_;
};

}  // namespace wbi::bench
