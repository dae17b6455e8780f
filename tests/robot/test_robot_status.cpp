// sim_robot in a wbi_host process; this process is the controller and the
// monitor: a command for an unknown joint or of the wrong size is rejected
// (counter and last_error on wbi/status, nothing applied), and a streaming
// joint left without commands trips the watchdog (on wbi/status) and holds;
// a simulation that diverges stops with an error and ends its process (exit 1).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;
using wbi::msg::ComponentStatus;
using wbi::msg::SensorSample;

std::uint64_t counter(const ComponentStatus& status, const std::string& name) {
  for (const auto& c : status.counters()) {
    if (c.name().to_string() == name) {
      return c.value();
    }
  }
  return 0;
}

// The arm (deploy/robots/arm.yaml) as component "arm" of a wbi_host child process,
// real-time, with this process's endpoints on its topics.
class RemoteArm {
 public:
  // extra_sim_config: YAML appended to deploy/robots/arm.yaml (e.g. pushes).
  explicit RemoteArm(const std::string& robot, const std::string& extra_sim_config = "")
      : robot_(robot),
        status_(participant_, topics::kStatus, qos::kStatus),
        sensors_(participant_, topics::sensors(robot), qos::kStream),
        commands_(participant_, topics::commands(robot), qos::kCommand) {
    const auto dir = wbi::test::binary_dir() / "tests";
    const auto file = dir / ("robot_status_" + robot + ".yaml");
    const auto sim_config = dir / ("robot_status_" + robot + "_sim.yaml");
    write_sim_config(sim_config, extra_sim_config);
    std::ofstream(file) << "status_period_s: 0.05\ncomponents:\n"
                        << "  - name: arm\n    type: sim_robot\n    parameters:\n"
                        << "      robot: " << robot << "\n      config: " << sim_config.string()
                        << "\n      watchdog_timeout_s: 0.1\n";
    host_ = std::make_unique<wbi::test::ChildProcess>(wbi::test::binary_dir() / "bin" / "wbi_host",
                                                      std::vector<std::string>{file.string()});
    EXPECT_TRUE(commands_.wait_for_subscribers(1, 30s)) << host_->output();
    EXPECT_TRUE(sensors_.wait_newer(sample_, 0, 30s)) << host_->output();
  }
  ~RemoteArm() { EXPECT_EQ(host_->stop(), expected_exit_code_) << host_->output(); }

  // A host that ends by itself: its exit code (nullopt while it still runs after `timeout`).
  std::optional<int> wait_exit(std::chrono::milliseconds timeout) {
    const auto code = host_->wait(timeout);
    if (code) {
      expected_exit_code_ = *code;
    }
    return code;
  }
  std::string output() { return host_->output(); }

  void send(const std::vector<unsigned short>& joints,
            const std::vector<wbi::msg::ControlMode>& modes, const std::vector<double>& values) {
    wbi::msg::ActuatorCommand command;
    command.header().robot(robot_);
    command.controller("pd");
    command.joints(joints);
    command.modes(modes);
    command.references(values);
    commands_.publish(command);
  }

  // The newest sensor sample at least `after_s` of robot time after `from`.
  const SensorSample& sample_after(const SensorSample& from, double after_s) {
    const auto until = from.header().stamp_ns() + static_cast<std::int64_t>(after_s * 1e9);
    const auto deadline = std::chrono::steady_clock::now() + 20s;
    while (sample_.sample.header().stamp_ns() < until &&
           std::chrono::steady_clock::now() < deadline) {
      sensors_.wait_newer(sample_, sample_.count, 1s);
    }
    EXPECT_GE(sample_.sample.header().stamp_ns(), until) << "robot time stands still";
    return sample_.sample;
  }
  SensorSample now() {
    sensors_.wait_newer(sample_, sample_.count, 5s);
    return sample_.sample;
  }

  // The first status of "arm" that satisfies `done` (bounded wait).
  ComponentStatus status_where(const std::function<bool(const ComponentStatus&)>& done) {
    wbi::dds::Received<ComponentStatus> got;
    const auto deadline = std::chrono::steady_clock::now() + 20s;
    while (std::chrono::steady_clock::now() < deadline) {
      if (status_.wait_newer(got, got.count, 1s) && got.sample.instance().to_string() == "arm" &&
          done(got.sample)) {
        return got.sample;
      }
    }
    ADD_FAILURE() << "no such status of 'arm'; last: " << got.sample.last_error() << "\n"
                  << host_->output();
    return got.sample;
  }

 private:
  // deploy/robots/arm.yaml with its URDF path made absolute, then `extra`.
  static void write_sim_config(const std::filesystem::path& to, const std::string& extra) {
    std::ifstream in(wbi::test::source_dir() / "deploy" / "robots" / "arm.yaml");
    std::ofstream out(to);
    std::string line;
    while (std::getline(in, line)) {
      out << (line.rfind("urdf:", 0) == 0
                  ? "urdf: " + wbi::test::project_model("arm7.urdf").string()
                  : line)
          << "\n";
    }
    out << extra;
  }

  std::string robot_;
  wbi::dds::Participant participant_{"robot_status_test"};
  wbi::dds::Subscriber<ComponentStatus> status_;
  wbi::dds::Subscriber<SensorSample> sensors_;
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands_;
  wbi::dds::Received<SensorSample> sample_;
  std::unique_ptr<wbi::test::ChildProcess> host_;
  int expected_exit_code_ = 0;  // of the SIGTERM the destructor sends
};

TEST(RobotStatus, RejectedCommandsAreOnTheStatusTopicAndNothingIsApplied) {
  RemoteArm arm("arm_rejects");
  const SensorSample settled = arm.sample_after(arm.now(), 0.3);  // holding its start posture
  const double q0 = settled.encoder_position()[0];
  // joint 0 is valid, 41 is not: the whole command is refused
  arm.send({0, 41}, {wbi::msg::POSITION, wbi::msg::POSITION}, {q0 + 1.0, 1.0});
  auto status = arm.status_where(
      [](const ComponentStatus& s) { return counter(s, "rejected_commands") >= 1; });
  EXPECT_EQ(status.last_error(),
            "command from 'pd' rejected: joint index 41 out of range (the robot has 7 joints)");
  // wrong size: two joints, one mode and one reference
  arm.send({0, 1}, {wbi::msg::POSITION}, {q0 + 1.0});
  status = arm.status_where(
      [](const ComponentStatus& s) { return counter(s, "rejected_commands") >= 2; });
  EXPECT_EQ(status.last_error(),
            "command from 'pd' rejected: 2 joints but 1 modes and 1 references");
  EXPECT_EQ(counter(status, "watchdog_trips"), 0u);
  // Had either been applied, joint 0 would move towards q0 + 1 at 0.5 rad/s.
  const SensorSample later = arm.sample_after(arm.now(), 0.5);
  EXPECT_NEAR(later.encoder_position()[0], q0, 0.01);
}

TEST(RobotStatus, WatchdogTripIsOnTheStatusTopicAndTheJointHolds) {
  RemoteArm arm("arm_watchdog");
  // One VELOCITY command, then silence: the joint moves for 0.1 s, then trips.
  arm.send({2}, {wbi::msg::VELOCITY}, {0.5});
  const auto status =
      arm.status_where([](const ComponentStatus& s) { return counter(s, "watchdog_trips") >= 1; });
  EXPECT_EQ(status.last_error(),
            "watchdog: joint 'joint_3' got no command for 0.1 s: holding its position");
  EXPECT_EQ(counter(status, "rejected_commands"), 0u);
  const SensorSample tripped = arm.now();
  // Still moving at 0.5 rad/s, it would travel 0.25 rad in 0.5 s.
  const SensorSample later = arm.sample_after(tripped, 0.5);
  EXPECT_NEAR(later.encoder_position()[2], tripped.encoder_position()[2], 0.01);
}

TEST(RobotStatus, DivergedSimulationEndsItsProcessWithTheErrorOnTheStatus) {
  // An absurd push makes the plant's state overflow to inf / NaN within a few steps.
  RemoteArm arm("arm_diverges",
                "pushes:\n  - {link: link_7, start: 0.2, duration: 0.05, force: [1e300, 0, 0]}\n");
  const auto status = arm.status_where([](const ComponentStatus& s) {
    return s.last_error().to_string().rfind("simulation stopped at t = ", 0) == 0;
  });
  EXPECT_NE(status.last_error().to_string().find("not finite"), std::string::npos)
      << status.last_error();
  // Then wbi_host shuts its components down and exits 1 (a launch's required
  // robot process failing), rather than serving a robot that no longer steps.
  const auto code = arm.wait_exit(30s);
  ASSERT_TRUE(code.has_value()) << "wbi_host still runs after the divergence\n" << arm.output();
  EXPECT_EQ(*code, 1) << arm.output();
  EXPECT_NE(arm.output().find("wbi_host: stopped (a component ended the process, exit code 1)"),
            std::string::npos)
      << arm.output();
}

}  // namespace
