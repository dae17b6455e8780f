// The actuator side's per-tick path allocates nothing once running: accepted
// commands, control ticks, and a watchdog trip reported on the status (the
// rejection of a bad command may allocate: it is an error path).
#include <gtest/gtest.h>

#include <algorithm>

#include <wbi/dds/participant.hpp>

#include "actuator_side.hpp"
#include "allocation_counter.hpp"
#include "two_joint_toy.hpp"

namespace {

TEST(ActuatorSide, CommandsTicksAndTripsDoNotAllocate) {
  const auto description = wbi::test::two_joint_description();
  wbi::dds::Participant participant("actuator_no_alloc");
  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  wbi::actuation::JointControllerConfig config;
  config.watchdog_timeout = 0.05;
  wbi::robot::ActuatorSide side(participant, "toy_no_alloc", description, config, report, events);
  wbi::actuation::SensorReadings readings;
  readings.resize(description);
  readings.position.setZero();
  readings.velocity.setZero();
  wbi::actuation::JointCommands out;
  out.resize(2);
  wbi::msg::ActuatorCommand command;
  command.header().robot("toy_no_alloc");
  command.controller("test");
  command.joints({0, 1});
  command.modes({wbi::msg::VELOCITY, wbi::msg::VELOCITY});
  command.references({0.1, -0.1});

  const auto period = wbi::actuation::Duration(1'000'000);  // 1 kHz
  std::int64_t tick = 0;
  // 100 ticks with a command each, then 100 without: the watchdog trips at 50 ms.
  const auto run = [&] {
    for (int k = 0; k < 200; ++k, ++tick) {
      const auto now = wbi::actuation::Time(tick * period.count());
      side.begin_tick(now);
      if (k < 100) {
        side.handle(command);
      }
      side.update(now, period, readings, out);
    }
  };
  run();  // warm-up: sizes the batch, the error text, the controller
  ASSERT_EQ(report.counter("watchdog_trips").value(), 2u);
  // Other threads of the process (DDS discovery) may allocate now and then:
  // a per-tick allocation shows in every window, noise in at most some.
  long fewest = -1;
  for (int window = 0; window < 3; ++window) {
    const long before = wbi::test::allocation_count();
    run();
    const long made = wbi::test::allocation_count() - before;
    fewest = fewest < 0 ? made : std::min(fewest, made);
  }
  EXPECT_EQ(fewest, 0) << "allocations per 200 ticks";
  EXPECT_EQ(report.counter("watchdog_trips").value(), 8u);  // both joints, once per run
  EXPECT_EQ(report.last_error(),
            "watchdog: joint 'b' got no command for 0.05 s: holding its position");
  EXPECT_EQ(report.counter("rejected_commands").value(), 0u);
  // Both joints trip in the same tick: one event naming both, per run.
  wbi::runtime::EventRecord event;
  int trips = 0;
  while (events.pop(event)) {
    ASSERT_EQ(event.kind, wbi::EventKind::watchdog_trip);
    EXPECT_STREQ(event.subject.data(), "a,b");
    ++trips;
  }
  EXPECT_EQ(trips, 4);
}

}  // namespace
