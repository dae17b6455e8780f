// Every field of ActuatorCommand and ControlParameters is checked by the
// actuator side (issue 26): each class of bad message is refused as a whole,
// counted, and named with its field and value; the log gets one line per
// (sender, kind) and a periodic summary, the status a counter per sender.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include <wbi/dds/participant.hpp>

#include "actuator_side.hpp"
#include "rejection_log.hpp"
#include "two_joint_toy.hpp"

namespace {

using wbi::ControlMode;
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// An actuator side of the robot "checked" (two joints a, b), ticked by hand.
struct Side {
  static constexpr const char* kRobot = "checked";
  wbi::dds::Participant participant{"command_checks"};
  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  wbi::robot::ActuatorSide side{participant, kRobot, wbi::test::two_joint_description(),
                                {},          report, events};
  wbi::actuation::SensorReadings readings;
  wbi::actuation::JointCommands out;
  std::int64_t tick = 0;

  Side() {
    readings.resize(wbi::test::two_joint_description());
    readings.position.setZero();
    readings.velocity.setZero();
    out.resize(2);
    side.hold(readings, wbi::actuation::Time(0));  // every joint in POSITION, as on activation
    update();
  }
  void update() {
    const auto now = wbi::actuation::Time(++tick * 1'000'000);
    side.begin_tick(now);
    side.update(now, wbi::actuation::Duration(1'000'000), readings, out);
  }
  std::uint64_t counter(const char* name) { return report.counter(name).value(); }
};

wbi::msg::ActuatorCommand good_command() {
  wbi::msg::ActuatorCommand c;
  c.header().robot(Side::kRobot);
  c.controller("pd");
  c.joints({0, 1});
  c.modes({wbi::msg::TORQUE, wbi::msg::TORQUE});
  c.references({1.0, -1.0});
  return c;
}

wbi::msg::ControlParameters good_parameters() {
  wbi::msg::ControlParameters p;
  p.header().robot(Side::kRobot);
  p.controller("pd");
  p.joints({0, 1});
  p.kp({10.0, 20.0});
  p.ki({0.0, 0.0});
  p.kd({1.0, 2.0});
  p.reference_speed({0.5, 0.5});
  return p;
}

struct BadCommand {
  const char* what;
  wbi::msg::ActuatorCommand command;
  const char* error;  // the rejection text must hold this
};

std::vector<BadCommand> bad_commands() {
  std::vector<BadCommand> bad;
  auto add = [&](const char* what, auto change, const char* error) {
    auto c = good_command();
    change(c);
    bad.push_back({what, c, error});
  };
  using C = wbi::msg::ActuatorCommand;
  add(
      "other robot", [](C& c) { c.header().robot("not-this-robot"); },
      "header.robot 'not-this-robot' is not this robot ('checked')");
  add(
      "no robot", [](C& c) { c.header().robot(""); }, "header.robot '' is not this robot");
  add(
      "robot name with control characters", [](C& c) { c.header().robot("a\nb\x1b[2J"); },
      "header.robot 'a?b?[2J' is not this robot");
  add(
      "mode outside the enum", [](C& c) { c.modes()[1] = static_cast<wbi::msg::ControlMode>(77); },
      "modes[1] = 77 is not a ControlMode");
  add(
      "NaN reference", [](C& c) { c.references()[0] = kNan; }, "references[0] = nan is not finite");
  add(
      "infinite reference", [](C& c) { c.references()[1] = -kInf; },
      "references[1] = -inf is not finite");
  add(
      "index out of range", [](C& c) { c.joints()[1] = 41; },
      "joint index 41 out of range (the robot has 2 joints)");
  add(
      "repeated joint", [](C& c) { c.joints()[1] = 0; }, "joint 'a' appears twice");
  add(
      "fewer modes", [](C& c) { c.modes().pop_back(); }, "2 joints but 1 modes and 2 references");
  add(
      "more references", [](C& c) { c.references().push_back(0.0); },
      "2 joints but 2 modes and 3 references");
  add(
      "empty", [](C& c) { c = C{}, c.header().robot(Side::kRobot); },
      "joints is empty: the command names no joint");
  return bad;
}

TEST(CommandChecks, EveryClassOfBadCommandIsRejectedNamedAndCounted) {
  Side s;
  std::uint64_t rejected = 0;
  for (const auto& bad : bad_commands()) {
    s.side.handle(bad.command);
    s.update();
    EXPECT_EQ(s.counter("rejected_commands"), ++rejected) << bad.what;
    EXPECT_NE(s.report.last_error().find(bad.error), std::string::npos)
        << bad.what << ": " << s.report.last_error();
    for (auto mode : s.side.status().mode) {
      EXPECT_EQ(mode, ControlMode::position) << bad.what << ": nothing applied (initial hold)";
    }
  }
  EXPECT_EQ(s.counter("rejected_from/pd"), rejected - 1);  // the empty one has no controller
  EXPECT_EQ(s.counter("rejected_from/(unnamed)"), 1u);
  s.side.handle(good_command());
  s.update();
  EXPECT_EQ(s.side.status().mode[0], ControlMode::torque);
  EXPECT_EQ(s.counter("rejected_commands"), rejected);
}

TEST(CommandChecks, EveryClassOfBadParametersIsRejectedNamedAndCounted) {
  Side s;
  const auto initial = s.side.gains(0);
  using P = wbi::msg::ControlParameters;
  struct Bad {
    const char* what;
    void (*change)(P&);
    const char* error;
  };
  const Bad bad[] = {
      {"other robot", [](P& p) { p.header().robot("arm"); },
       "header.robot 'arm' is not this robot ('checked')"},
      {"no joints", [](P& p) { p.joints().clear(); }, "joints is empty"},
      {"index out of range", [](P& p) { p.joints()[1] = 9; },
       "joint index 9 out of range (the robot has 2 joints)"},
      {"repeated joint", [](P& p) { p.joints()[1] = 0; },
       "joint 'a' appears twice (joints[0] and joints[1])"},
      {"kp length", [](P& p) { p.kp().pop_back(); }, "kp has 1 values for 2 joints"},
      {"reference_speed length", [](P& p) { p.reference_speed().push_back(1.0); },
       "reference_speed has 3 values for 2 joints"},
      {"negative kp", [](P& p) { p.kp()[1] = -3.0; },
       "kp[1] = -3 for joint 'b' must be finite and ≥ 0"},
      {"negative ki", [](P& p) { p.ki()[0] = -1e-3; }, "ki[0] = -0.001 for joint 'a'"},
      {"infinite kd", [](P& p) { p.kd()[0] = kInf; }, "kd[0] = inf for joint 'a'"},
      {"zero speed", [](P& p) { p.reference_speed()[1] = 0.0; },
       "reference_speed[1] = 0 for joint 'b' must be finite and > 0"},
      {"negative speed", [](P& p) { p.reference_speed()[0] = -1.0; }, "reference_speed[0] = -1"},
      {"nothing set",
       [](P& p) {
         p.kp().clear();
         p.ki().clear();
         p.kd().clear();
         p.reference_speed().clear();
       },
       "the parameters set nothing"},
  };
  std::uint64_t rejected = 0;
  for (const auto& b : bad) {
    auto p = good_parameters();
    b.change(p);
    s.side.handle(p);
    EXPECT_EQ(s.counter("rejected_parameters"), ++rejected) << b.what;
    EXPECT_NE(s.report.last_error().find(b.error), std::string::npos)
        << b.what << ": " << s.report.last_error();
    EXPECT_EQ(s.side.gains(0).kp, initial.kp) << b.what << ": nothing applied";
  }
  EXPECT_EQ(s.counter("rejected_from/pd"), rejected);
  // NaN: unchanged (what wbi_proxy sends for what it does not set)
  auto p = good_parameters();
  p.kp()[0] = kNan;
  s.side.handle(p);
  EXPECT_EQ(s.counter("rejected_parameters"), rejected);
  EXPECT_EQ(s.side.gains(0).kp, initial.kp);
  EXPECT_EQ(s.side.gains(0).kd, 1.0);
  EXPECT_EQ(s.side.gains(1).kp, 20.0);
}

// Valid but extreme: a denormal reference speed (> 0), gains of 1e300, a
// torque of 1e300 and a target far beyond the limits. Accepted; the outputs
// stay finite and within the effort limit.
TEST(CommandChecks, ExtremeValidValuesKeepTheOutputsFinite) {
  Side s;
  auto p = good_parameters();
  p.kp({1e300, 1e300});
  p.kd({1e300, 0.0});
  p.ki({1e300, 0.0});
  p.reference_speed({4.9e-324, 1e300});
  s.side.handle(p);
  EXPECT_EQ(s.counter("accepted_parameters"), 1u) << s.report.last_error();
  auto c = good_command();
  c.modes({wbi::msg::POSITION, wbi::msg::TORQUE});
  c.references({1e300, -1e300});
  s.readings.velocity << 1.0, -1.0;  // moving: every PID term is large
  for (int k = 0; k < 50; ++k) {
    s.side.handle(c);
    c.references()[0] = -c.references()[0];  // a new target every tick
    s.update();
    for (int j = 0; j < 2; ++j) {
      ASSERT_TRUE(std::isfinite(s.out.value[j])) << "tick " << k << " joint " << j;
      ASSERT_LE(std::abs(s.out.value[j]), 50.0);
      ASSERT_TRUE(std::isfinite(s.side.status().position_reference[j]));
    }
  }
  EXPECT_EQ(s.counter("accepted_commands"), 50u);
  EXPECT_EQ(s.counter("limit_clamps"), 100u);
}

TEST(RejectionLog, KindMasksNumbersAndNames) {
  using wbi::robot::RejectionLog;
  EXPECT_EQ(RejectionLog::kind_of("joint index 41 out of range (the robot has 7 joints)"),
            "joint index # out of range (the robot has # joints)");
  EXPECT_EQ(RejectionLog::kind_of("kp[1] = -3.5e+12 for joint 'r_knee' must be finite"),
            "kp[#] = # for joint '…' must be finite");
  EXPECT_EQ(RejectionLog::kind_of("header.robot 'x' is not this robot ('arm')"),
            "header.robot '…' is not this robot ('…')");
  EXPECT_EQ(RejectionLog::printable(std::string("a\nb\x1b", 4)), "a?b?");
  EXPECT_EQ(RejectionLog::printable(""), "(unnamed)");
  EXPECT_EQ(RejectionLog::printable("r_knee ≥ 0"), "r_knee ≥ 0");  // UTF-8 stays
}

// One line per (sender, kind), whatever the rate; a summary per period with
// the counts; a counter per sender on the status.
TEST(RejectionLog, OneLinePerSenderAndKindThenPeriodicSummaries) {
  using wbi::robot::RejectionLog;
  wbi::runtime::StatusReport report;
  std::ostringstream log;
  const auto t0 = RejectionLog::Clock::now();
  {
    RejectionLog rejections(report, log, std::chrono::seconds(10));
    for (int k = 0; k < 5000; ++k) {  // 5 s of a bad publisher at 1 kHz
      const auto now = t0 + std::chrono::milliseconds(k);
      rejections.reject(
          "command", "bad",
          "joint index " + std::to_string(40 + k % 3) + " out of range (the robot has 2 joints)",
          now);
      if (k % 2 == 0) {
        rejections.reject("control parameters", "bad", "kp[0] = -1 for joint 'a' must be ≥ 0", now);
      }
    }
    EXPECT_EQ(rejections.lines(), 2u) << log.str();
    EXPECT_EQ(report.counter("rejected_from/bad").value(), 7500u);
    EXPECT_EQ(rejections.count("bad"), 7500u);
    // a second sender has its own line and counter
    rejections.reject("command", "other", "joint index 40 out of range (the robot has 2 joints)",
                      t0 + std::chrono::milliseconds(5000));
    EXPECT_EQ(rejections.lines(), 3u);
    EXPECT_EQ(report.counter("rejected_from/other").value(), 1u);
    // 10 s on: the summary of both kinds of 'bad' ('other' had one, logged)
    rejections.reject("command", "bad", "joint index 40 out of range (the robot has 2 joints)",
                      t0 + std::chrono::seconds(11));
    EXPECT_EQ(rejections.lines(), 5u) << log.str();
  }
  const std::string text = log.str();
  EXPECT_NE(text.find("command from 'bad' rejected: joint index 40 out of range (the robot has 2 "
                      "joints) (repeats of this from 'bad' are counted: summary every 10 s)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("rejected from 'bad' in the last 11 s: 5000 × command: joint index # out "
                      "of range (the robot has # joints) (5001 in all)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("2499 × control parameters: kp[#] = # for joint '…' must be ≥ # (2500 in "
                      "all)"),
            std::string::npos)
      << text;
}

// The first rejection of a burst (of one kind from one sender) is told to the
// caller, who makes it an event: a new kind, a new sender, or one after a pause.
TEST(RejectionLog, SaysWhichRejectionStartsABurst) {
  using wbi::robot::RejectionLog;
  wbi::runtime::StatusReport report;
  std::ostringstream log;
  RejectionLog rejections(report, log);
  const auto t0 = RejectionLog::Clock::now();
  const auto at = [&](int ms) { return t0 + std::chrono::milliseconds(ms); };
  EXPECT_TRUE(rejections.reject("command", "bad", "joint index 40 out of range", at(0)));
  for (int ms = 1; ms < 900; ++ms) {  // a stream with gaps shorter than kBurstGap
    EXPECT_FALSE(rejections.reject("command", "bad", "joint index 41 out of range", at(ms)));
  }
  EXPECT_TRUE(rejections.reject("command", "bad", "mode 9 not in the enum", at(900)));
  EXPECT_TRUE(rejections.reject("command", "other", "joint index 40 out of range", at(900)));
  EXPECT_TRUE(rejections.reject("command", "bad", "joint index 40 out of range", at(2000)));
}

// Many senders and many kinds: the status keeps room for the owner's own
// counters, and the log stays bounded.
TEST(RejectionLog, SendersAndKindsAreBounded) {
  using wbi::robot::RejectionLog;
  wbi::runtime::StatusReport report;
  for (const char* own : {"rejected_commands", "rejected_parameters", "watchdog_trips",
                          "limit_clamps", "lockstep_timeouts"}) {
    report.counter(own);
  }
  std::ostringstream log;
  RejectionLog rejections(report, log);
  for (int sender = 0; sender < 100; ++sender) {
    for (int kind = 0; kind < 3; ++kind) {
      rejections.reject("command", "fuzz" + std::to_string(sender),
                        "kind " + std::string(1, static_cast<char>('a' + kind)));
    }
  }
  EXPECT_LE(report.counter_count(), wbi::runtime::StatusReport::kMaxCounters - 1);
  EXPECT_EQ(report.counter("rejected_from/fuzz0").value(), 3u);
  EXPECT_EQ(report.counter("rejected_from/(other senders)").value(),
            300u - 3u * RejectionLog::kMaxSenders);
  // the first kMaxSenders each, and the others together: three kinds each
  EXPECT_EQ(rejections.lines(), 3 * (RejectionLog::kMaxSenders + 1));
  // and whatever the kinds, the table is bounded
  for (int kind = 0; kind < 200; ++kind) {
    rejections.reject(
        "command", "fuzz0",
        "kind " + std::string(1 + kind / 26, 'a') + static_cast<char>('a' + kind % 26));
  }
  EXPECT_LE(rejections.lines(), RejectionLog::kMaxKinds + 1);  // + "further kinds are counted"
}

}  // namespace
