#include "latency_observer.hpp"

#include <chrono>

#include <wbi/dds/source_clock.hpp>
#include <wbi/dds/topics.hpp>

namespace wbi::bench {

LatencyObserver::LatencyObserver(dds::Participant& participant, const std::string& robot,
                                 const std::string& controller_instance, std::size_t max_samples)
    : controller_instance_(controller_instance),
      max_samples_(max_samples),
      // A best-effort reader (the status profile's) matches the sensor writers
      // of any deploy, reliable or best effort (deploy/qos_realtime.xml).
      sensors_(participant, dds::topics::sensors(robot), dds::qos::kStatus,
               [this](const msg::SensorSample& sample, const dds::detail::SampleInfo& info) {
                 on_sensor(sample, info);
               }),
      states_(participant, dds::topics::state(robot), dds::qos::kStatus,
              [this](const msg::StateEstimate& state, const dds::detail::SampleInfo& info) {
                on_state(state, info);
              }),
      commands_(participant, dds::topics::commands(robot), dds::qos::kCommand,
                [this](const msg::ActuatorCommand& command, const dds::detail::SampleInfo& info) {
                  on_command(command, info);
                }),
      status_(participant, dds::topics::kStatus, dds::qos::kStatus,
              [this](const msg::ComponentStatus& status, const dds::detail::SampleInfo&) {
                on_status(status);
              }) {
  for (auto* v : {&result_.latencies_us, &result_.to_state_us, &result_.to_command_us,
                  &result_.delivery_us}) {
    v->reserve(max_samples_);
  }
}

// A sensor sample's slot is its sequence number (the robot's tick), which a
// command carries back as its tick; the stamp confirms the match.
void LatencyObserver::on_sensor(const msg::SensorSample& sample,
                                const dds::detail::SampleInfo& info) {
  std::lock_guard lock(mutex_);
  seen_[sample.header().seq() % kSlots] = {sample.header().stamp_ns(), info.source_stamp_ns, 0};
  ++result_.sensor_samples;
}

// The estimator copies the sensor sample's seq and stamp into its estimate.
void LatencyObserver::on_state(const msg::StateEstimate& state,
                               const dds::detail::SampleInfo& info) {
  std::lock_guard lock(mutex_);
  Seen& sensor = seen_[state.header().seq() % kSlots];
  if (sensor.stamp_ns == state.header().stamp_ns()) {
    sensor.state_published_ns = info.source_stamp_ns;
  }
}

void LatencyObserver::on_command(const msg::ActuatorCommand& command,
                                 const dds::detail::SampleInfo& info) {
  const std::int64_t arrived_ns = dds::source_clock_now_ns();
  std::lock_guard lock(mutex_);
  ++result_.commands;
  const Seen& sensor = seen_[command.tick() % kSlots];
  if (command.source_stamp_ns() == 0 || sensor.stamp_ns != command.source_stamp_ns()) {
    ++result_.unmatched_commands;
    return;
  }
  if (result_.latencies_us.size() < max_samples_) {
    result_.latencies_us.push_back(1e-3 * static_cast<double>(arrived_ns - sensor.published_ns));
    result_.delivery_us.push_back(1e-3 * static_cast<double>(arrived_ns - info.source_stamp_ns));
    if (sensor.state_published_ns != 0) {  // the estimate may reach us after the command
      result_.to_state_us.push_back(
          1e-3 * static_cast<double>(sensor.state_published_ns - sensor.published_ns));
      result_.to_command_us.push_back(
          1e-3 * static_cast<double>(info.source_stamp_ns - sensor.state_published_ns));
    }
  }
}

void LatencyObserver::on_status(const msg::ComponentStatus& status) {
  if (status.instance() != controller_instance_) {
    return;
  }
  std::lock_guard lock(mutex_);
  // The newest report counts; a restarted loop would start from 0 again.
  if (status.iterations() >= result_.ticks) {
    result_.ticks = status.iterations();
    result_.overruns = status.overruns();
    result_.status_stamp_ns = status.header().stamp_ns();
  }
}

double LatencyObserver::loop_rate_hz(const Result& before, const Result& after) {
  if (before.status_stamp_ns == 0) {
    return 0.0;  // no report yet at `before`
  }
  const double seconds = 1e-9 * static_cast<double>(after.status_stamp_ns - before.status_stamp_ns);
  return seconds > 0.0 ? static_cast<double>(after.ticks - before.ticks) / seconds : 0.0;
}

LatencyObserver::Result LatencyObserver::result() const {
  std::lock_guard lock(mutex_);
  return result_;
}

}  // namespace wbi::bench
