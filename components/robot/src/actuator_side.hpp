// The actuator side of a robot on DDS: subscribes to the robot's commands and
// control parameters, answers joint claims (claim_desk.hpp: a command or
// control parameters for a joint held by another controller is refused), runs the joint-level
// controller (wbi::actuation:: JointController: modes, PID, limits, watchdog) at the backend rate,
// and reports on the owner component's status (StatusReport):
//   accepted_commands    commands applied (staged for the next tick)
//   accepted_parameters  control parameters applied
//   rejected_commands    commands refused (header.robot not this robot, mode
//                        not in the enum, unknown joint index, sizes that
//                        disagree, non-finite values…): nothing of them is applied
//   rejected_parameters  control parameters refused (same checks, and gains
//                        finite and ≥ 0, speeds > 0): none of them applied
//   rejected_from/<sender>  both, per sending controller (rejection_log.hpp)
//   watchdog_trips       streaming joints that got no command in time (they hold)
//   limit_clamps         command values outside the joint's limits (clamped)
// and the last rejection or trip, in words, as the last error, e.g.
//   command from 'pd' rejected: joint index 41 out of range (the robot has 7 joints)
// The log gets the first rejection of each kind per sender and a periodic
// summary (RejectionLog): a bad publisher cannot flood it.
// Events (wbi/events, the owner's EventLog): WATCHDOG_TRIP, one per tick that
// tripped joints, naming them; COMMANDS_REJECTED, one per burst of one kind
// from one sender (RejectionLog::reject); and the claim desk's.
// One implementation, used by sim_robot and by the driver component.
//
// Threads: commands and parameters arrive on DDS threads; begin_tick() and
// update() run on the owner's loop. update() never allocates.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include <wbi/msg/commands.h>
#include <wbi/actuation/joint_controller.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/status_report.hpp>

#include "claim_desk.hpp"
#include "joint_claims.hpp"
#include "rejection_log.hpp"

namespace wbi::robot {

class ActuatorSide {
 public:
  // Called on the DDS thread after each command was handled (accepted or not),
  // e.g. for lockstep bookkeeping, with its DDS source timestamp [ns].
  using CommandObserver =
      std::function<void(const wbi::msg::ActuatorCommand&, std::int64_t written_ns)>;

  ActuatorSide(dds::Participant& participant, const std::string& robot,
               const actuation::BackendDescription& description,
               const actuation::JointControllerConfig& config, runtime::StatusReport& report,
               runtime::EventLog& events, CommandObserver observer = {},
               bool require_claims = false);
  ~ActuatorSide();  // unsubscribes first: no callback runs after this
  ActuatorSide(const ActuatorSide&) = delete;
  ActuatorSide& operator=(const ActuatorSide&) = delete;

  // Every joint holds its measured position (POSITION mode) until commanded.
  void hold(const actuation::SensorReadings& readings, actuation::Time now);
  // The time of the tick now starting: the arrival time given to commands (watchdog).
  void begin_tick(actuation::Time now) { now_ns_ = now.count(); }
  // One control tick: applies the commands staged since the last one, runs the
  // watchdog and the loops, writes `out`, updates the counters.
  void update(actuation::Time now, actuation::Duration period, const actuation::SensorReadings& in,
              actuation::JointCommands& out);

  // What the subscriptions call for each message (any thread; never throw).
  // Accepted commands do not allocate.
  // `writer` is the sending writer's GUID: with the message's controller name,
  // who must own every joint the message names (joint_claims.hpp).
  // (Tests that feed the side directly leave it zero: one participant.)
  // `written_ns`: the command's DDS source timestamp, passed to the observer.
  void handle(const wbi::msg::ActuatorCommand& command, const dds::detail::Guid& writer = {},
              std::int64_t written_ns = 0);
  void handle(const wbi::msg::ControlParameters& message, const dds::detail::Guid& writer = {});

  const actuation::JointControlStatus& status() const { return controller_.status(); }
  // The gains in use (control parameters change them); read where no message is handled.
  const actuation::PidGains& gains(int joint) const { return controller_.gains(joint); }

 private:
  void report_new_trips();
  // Counts (in `counter`), reports and logs a refused message (after mutex_ is released).
  void reject(runtime::StatusCounter& counter, std::string_view what, const std::string& topic,
              const wbi::msg::BoundedName& sender, const std::string& error);

  const std::string robot_;                              // header.robot every message must carry
  const std::string commands_topic_, parameters_topic_;  // events' subjects
  const std::vector<std::string> joint_names_;
  const double watchdog_timeout_s_;
  const bool damp_on_trip_;
  actuation::JointController controller_;
  std::vector<double> reference_speed_;    // [n] POSITION-mode speed per joint
  actuation::JointCommandBatch batch_;     // reused for every command
  std::vector<std::uint8_t> was_tripped_;  // [n] at the previous tick
  std::uint64_t clamps_seen_ = 0;
  std::atomic<std::int64_t> now_ns_{0};
  std::mutex mutex_;  // guards controller_, batch_, reference_speed_, claims_ (DDS threads vs loop)
  JointClaims claims_;

  runtime::StatusReport& report_;
  runtime::EventLog& events_;
  runtime::StatusCounter& accepted_commands_;
  runtime::StatusCounter& accepted_parameters_;
  runtime::StatusCounter& rejected_commands_;
  runtime::StatusCounter& rejected_parameters_;
  runtime::StatusCounter& watchdog_trips_;
  runtime::StatusCounter& limit_clamps_;
  RejectionLog rejections_;
  CommandObserver observer_;

  std::unique_ptr<ClaimDesk> claim_desk_;
  std::unique_ptr<dds::Subscriber<wbi::msg::ActuatorCommand>> commands_;
  std::unique_ptr<dds::Subscriber<wbi::msg::ControlParameters>> parameters_;
};

}  // namespace wbi::robot
