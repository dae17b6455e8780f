#include "actuator_side.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include <wbi/dds/topics.hpp>

#include "command_translation.hpp"

namespace wbi::robot {

ActuatorSide::ActuatorSide(dds::Participant& participant, const std::string& robot,
                           const actuation::BackendDescription& description,
                           const actuation::JointControllerConfig& config,
                           runtime::StatusReport& report, runtime::EventLog& events,
                           CommandObserver observer, bool require_claims)
    : robot_(robot),
      commands_topic_(dds::topics::commands(robot)),
      parameters_topic_(dds::topics::control_parameters(robot)),
      joint_names_(description.joint_names),
      watchdog_timeout_s_(config.watchdog_timeout),
      damp_on_trip_(config.watchdog_action == actuation::WatchdogAction::kDamp),
      controller_(description, config),
      reference_speed_(description.joint_names.size(), config.reference_speed),
      was_tripped_(description.joint_names.size(), 0),
      claims_(description.joint_names, static_cast<std::int64_t>(config.watchdog_timeout * 1e9),
              require_claims),
      report_(report),
      events_(events),
      accepted_commands_(report.counter("accepted_commands")),
      accepted_parameters_(report.counter("accepted_parameters")),
      rejected_commands_(report.counter("rejected_commands")),
      rejected_parameters_(report.counter("rejected_parameters")),
      watchdog_trips_(report.counter("watchdog_trips")),
      limit_clamps_(report.counter("limit_clamps")),
      rejections_(report, std::cerr),
      observer_(std::move(observer)) {
  // Claims and subscribers last: their callbacks use everything above.
  claim_desk_ = std::make_unique<ClaimDesk>(participant, robot, claims_, mutex_, now_ns_, report,
                                            events, rejections_);
  commands_ = std::make_unique<dds::Subscriber<wbi::msg::ActuatorCommand>>(
      participant, commands_topic_, dds::qos::kCommand,
      [this](const wbi::msg::ActuatorCommand& c, const dds::detail::SampleInfo& info) {
        handle(c, info.writer, info.source_stamp_ns);
      });
  parameters_ = std::make_unique<dds::Subscriber<wbi::msg::ControlParameters>>(
      participant, parameters_topic_, dds::qos::kCommand,
      [this](const wbi::msg::ControlParameters& p, const dds::detail::SampleInfo& info) {
        handle(p, info.writer);
      });
}

ActuatorSide::~ActuatorSide() {
  commands_.reset();
  parameters_.reset();
  claim_desk_.reset();
}

void ActuatorSide::hold(const actuation::SensorReadings& readings, actuation::Time now) {
  // Like a real robot's boards: joints hold where they are until a controller
  // commands them (no watchdog: POSITION is not a streaming mode).
  actuation::JointCommandBatch hold;
  hold.modes.assign(joint_names_.size(), wbi::ControlMode::position);
  hold.values.assign(readings.position.data(), readings.position.data() + readings.position.size());
  std::lock_guard lock(mutex_);
  const auto result = controller_.submit(hold, now);
  if (!result.ok) {
    throw std::runtime_error("cannot hold the initial posture: " + result.error);
  }
}

// Runs on a DDS thread: stages the command for the next tick; never throws into DDS.
// The loop waits for mutex_ only while the command is checked and staged; a
// rejection is reported after it is released.
void ActuatorSide::handle(const wbi::msg::ActuatorCommand& command, const dds::detail::Guid& writer,
                          std::int64_t written_ns) {
  const auto sender =
      Claimant::of(writer.data(), {command.controller().c_str(), command.controller().size()});
  const std::span<const std::uint16_t> joints(command.joints().data(), command.joints().size());
  std::string error;
  {
    std::lock_guard lock(mutex_);
    error = to_batch(command, robot_, reference_speed_, batch_);
    if (const int refused = error.empty() ? claims_.first_refused(sender, joints) : -1;
        refused >= 0) {
      error = claims_.refusal(sender, joints[refused]);
    }
    if (error.empty()) {
      const std::int64_t now_ns = now_ns_.load();
      auto result = controller_.submit(batch_, actuation::Time(now_ns));
      if (result.ok) {
        claims_.commanded(sender, joints, now_ns);
        accepted_commands_.add();
        limit_clamps_.add(static_cast<std::uint64_t>(result.clamped));
      } else {
        error = std::move(result.error);
      }
    }
  }
  if (!error.empty()) {
    reject(rejected_commands_, "command", commands_topic_, command.controller(), error);
  }
  if (observer_) {
    observer_(command, written_ns);
  }
}

// Runs on a DDS thread. Every field is checked first: a bad message changes nothing.
void ActuatorSide::handle(const wbi::msg::ControlParameters& message,
                          const dds::detail::Guid& writer) {
  const auto sender =
      Claimant::of(writer.data(), {message.controller().c_str(), message.controller().size()});
  const std::span<const std::uint16_t> joints(message.joints().data(), message.joints().size());
  std::string error;
  {
    std::lock_guard lock(mutex_);
    error = check_parameters(message, robot_, joint_names_);
    if (const int refused = error.empty() ? claims_.first_refused(sender, joints) : -1;
        refused >= 0) {
      error = claims_.refusal(sender, joints[refused]);
    }
    if (error.empty()) {
      for (std::size_t k = 0; k < message.joints().size(); ++k) {
        const auto joint = message.joints()[k];
        const auto value = [&](const std::vector<double>& values, double current) {
          return !values.empty() && !std::isnan(values[k]) ? values[k] : current;  // NaN: unchanged
        };
        auto gains = controller_.gains(joint);
        gains.kp = value(message.kp(), gains.kp);
        gains.ki = value(message.ki(), gains.ki);
        gains.kd = value(message.kd(), gains.kd);
        controller_.set_gains(joint_names_[joint], gains);
        reference_speed_[joint] = value(message.reference_speed(), reference_speed_[joint]);
      }
      accepted_parameters_.add();
    }
  }
  if (!error.empty()) {
    reject(rejected_parameters_, "control parameters", parameters_topic_, message.controller(),
           error);
  }
}

void ActuatorSide::reject(runtime::StatusCounter& counter, std::string_view what,
                          const std::string& topic, const wbi::msg::BoundedName& sender,
                          const std::string& error) {
  const std::string_view name(sender.c_str(), sender.size());
  const std::string text = RejectionLog::without_control_characters(error);  // may quote the wire
  const std::string line =
      std::string(what) + " from '" + RejectionLog::printable(name) + "' rejected: " + text;
  counter.add();
  report_.set_error(line);
  if (rejections_.reject(what, name, text)) {
    events_.emit(EventSeverity::warning, EventKind::commands_rejected, line, topic);
  }
}

void ActuatorSide::update(actuation::Time now, actuation::Duration period,
                          const actuation::SensorReadings& in, actuation::JointCommands& out) {
  {
    std::lock_guard lock(mutex_);
    controller_.update(now, period, in, out);
  }
  watchdog_trips_.set(controller_.status().watchdog_trips);
  report_new_trips();
}

// A joint that tripped in this tick becomes the last error; the joints that
// tripped in this tick are one WATCHDOG_TRIP event. Formatted into fixed
// buffers: a trip on the loop thread does not allocate.
void ActuatorSide::report_new_trips() {
  const auto& tripped = controller_.status().watchdog_tripped;
  char joints[runtime::EventRecord::kMaxText + 1];
  std::size_t joints_length = 0;  // of "j1,j2", cut at the buffer's end
  int count = 0;
  for (std::size_t i = 0; i < tripped.size(); ++i) {
    if (tripped[i] != 0 && was_tripped_[i] == 0) {
      char text[256];
      const int length =
          std::snprintf(text, sizeof text, "watchdog: joint '%s' got no command for %g s: %s",
                        joint_names_[i].c_str(), watchdog_timeout_s_,
                        damp_on_trip_ ? "damped to rest" : "holding its position");
      report_.set_error(std::string_view(
          text, std::clamp<std::size_t>(static_cast<std::size_t>(length), 0, sizeof text - 1)));
      const int added = std::snprintf(joints + joints_length, sizeof joints - joints_length, "%s%s",
                                      count > 0 ? "," : "", joint_names_[i].c_str());
      joints_length =
          std::min(joints_length + static_cast<std::size_t>(std::max(added, 0)), sizeof joints - 1);
      ++count;
    }
    was_tripped_[i] = tripped[i];
  }
  if (count > 0) {
    char text[160];
    std::snprintf(text, sizeof text, "%d joint(s) got no command for %g s: %s", count,
                  watchdog_timeout_s_, damp_on_trip_ ? "damped to rest" : "holding their position");
    events_.emit(EventSeverity::warning, EventKind::watchdog_trip, text,
                 std::string_view(joints, joints_length));
  }
}

}  // namespace wbi::robot
