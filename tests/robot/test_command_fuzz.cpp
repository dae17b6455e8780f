// Wire fuzz (issue 26): the arm (sim_robot, real time) runs in a wbi_host
// process; this process publishes random and adversarial ActuatorCommand and
// ControlParameters samples at 1 kHz for 3 s — sizes up to the IDL bounds,
// indices, enum values, NaN/inf/denormals/huge values, other robot names,
// controller names of the maximum length and of any bytes — each built to be
// valid or to break exactly one rule. The robot must not crash, count every
// sample it got as accepted or rejected (exactly the ones built so when none
// was lost on the way), and afterwards obey a good controller.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <thread>

#include <wbi/msg/description.h>
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

constexpr const char* kRobot = "arm_fuzz";
constexpr int kJoints = 7;
constexpr std::size_t kMaxJoints = 128;  // idl/common.idl MAX_JOINTS
constexpr std::size_t kMaxName = 64;     // MAX_NAME

std::uint64_t counter(const ComponentStatus& status, const std::string& name) {
  for (const auto& c : status.counters()) {
    if (c.name().to_string() == name) {
      return c.value();
    }
  }
  return 0;
}

// Random samples, each valid or broken in exactly one way (its verdict known).
class Fuzzer {
 public:
  explicit Fuzzer(std::uint64_t seed) : rng_(seed) {}

  // A command; `valid` tells whether the robot must accept it.
  wbi::msg::ActuatorCommand command(bool& valid) {
    wbi::msg::ActuatorCommand c;
    c.header().robot(kRobot);
    c.header().seq(seq_++);
    c.controller(controller_name());
    c.tick(rng_());
    c.source_stamp_ns(static_cast<std::int64_t>(rng_()));
    const auto joints = distinct_joints();
    c.joints(joints);
    for (std::size_t k = 0; k < joints.size(); ++k) {
      c.modes().push_back(static_cast<wbi::msg::ControlMode>(pick(6)));
      c.references().push_back(finite_value());
    }
    valid = pick(3) == 0;  // a third valid, the rest broken in one way
    if (!valid) {
      switch (pick(8)) {
        case 0:
          c.header().robot(pick(4) == 0 ? std::string() : random_name(1 + pick(kMaxName)));
          break;
        case 1:
          c.modes()[pick(joints.size())] = static_cast<wbi::msg::ControlMode>(
              6 + pick(std::numeric_limits<std::uint32_t>::max() - 6));
          break;
        case 2:
          c.references()[pick(joints.size())] = non_finite();
          break;
        case 3:
          c.joints()[pick(joints.size())] =
              static_cast<unsigned short>(kJoints + pick(65536 - kJoints));
          break;
        case 4:
          if (joints.size() < 2) {
            c.joints().push_back(joints[0]);
            c.modes().push_back(wbi::msg::IDLE);
            c.references().push_back(0.0);
          } else {
            c.joints()[1] = c.joints()[0];
          }
          break;
        case 5:
          c.modes().resize(other_size(joints.size()), wbi::msg::TORQUE);
          break;
        case 6:
          c.references().resize(other_size(joints.size()), 1.0);
          break;
        default:
          c.joints().clear();
          c.modes().resize(pick(2) * pick(kMaxJoints));
          c.references().resize(c.modes().size());
          break;
      }
    }
    return c;
  }

  wbi::msg::ControlParameters parameters(bool& valid) {
    wbi::msg::ControlParameters p;
    p.header().robot(kRobot);
    p.header().seq(seq_++);
    p.controller(controller_name());
    const auto joints = distinct_joints();
    p.joints(joints);
    // Gains from none to 1e300; NaN: unchanged. Speeds from denormal to huge.
    auto gains = [&](std::vector<double>& out, bool speed) {
      for (std::size_t k = 0; k < joints.size(); ++k) {
        const double choices[] = {std::numeric_limits<double>::quiet_NaN(), speed ? 4.9e-324 : 0.0,
                                  uniform(speed ? 0.05 : 0.0, 500.0), 1e300,
                                  std::numeric_limits<double>::denorm_min()};
        out.push_back(choices[pick(5)]);
      }
    };
    gains(p.kp(), false);
    gains(p.ki(), false);
    gains(p.kd(), false);
    gains(p.reference_speed(), true);
    valid = pick(3) == 0;
    if (!valid) {
      const std::size_t k = pick(joints.size());
      switch (pick(7)) {
        case 0:
          p.header().robot(random_name(1 + pick(kMaxName)));
          break;
        case 1:
          p.joints()[k] = static_cast<unsigned short>(kJoints + pick(65536 - kJoints));
          break;
        case 2:
          (pick(2) == 0 ? p.kp() : p.kd())[k] = -uniform(1e-300, 1e300);
          break;
        case 3:
          p.ki()[k] = pick(2) == 0 ? INFINITY : -INFINITY;
          break;
        case 4:
          p.reference_speed()[k] = pick(2) == 0 ? 0.0 : -uniform(0.0, 10.0);
          break;
        case 5:
          p.kd().resize(other_size(joints.size()), 1.0);
          break;
        default:
          p.joints().clear();
          break;
      }
    }
    return p;
  }

 private:
  std::size_t pick(std::size_t n) {
    return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_);
  }
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }

  std::vector<unsigned short> distinct_joints() {
    std::vector<unsigned short> all(kJoints);
    std::iota(all.begin(), all.end(), 0);
    std::shuffle(all.begin(), all.end(), rng_);
    all.resize(1 + pick(kJoints));
    return all;
  }
  // Any size up to MAX_JOINTS but `not_this`.
  std::size_t other_size(std::size_t not_this) {
    const std::size_t s = pick(kMaxJoints);
    return s >= not_this ? s + 1 : s;
  }
  double finite_value() {
    const double choices[] = {0.0,
                              -0.0,
                              uniform(-3.0, 3.0),
                              1e300,
                              -1e300,
                              std::numeric_limits<double>::denorm_min(),
                              std::numeric_limits<double>::max(),
                              uniform(-1.0, 1.0)};
    return choices[pick(8)];
  }
  double non_finite() {
    const double choices[] = {std::numeric_limits<double>::quiet_NaN(), INFINITY, -INFINITY,
                              -std::numeric_limits<double>::quiet_NaN()};
    return choices[pick(4)];
  }
  // Any bytes but NUL (the bounded string would end there).
  std::string random_name(std::size_t length) {
    std::string name(length, ' ');
    for (char& c : name) {
      c = static_cast<char>(1 + pick(255));
    }
    return name;
  }
  std::string controller_name() {
    switch (pick(4)) {
      case 0:
        return std::string(kMaxName, 'c');  // the maximum length
      case 1:
        return random_name(1 + pick(kMaxName));
      case 2:
        return "";
      default:
        return "fuzz" + std::to_string(pick(3));
    }
  }

  std::mt19937_64 rng_;
  std::uint64_t seq_ = 0;
};

// deploy/robots/arm.yaml with its URDF path made absolute.
std::filesystem::path arm_config() {
  const auto to = wbi::test::binary_dir() / "tests" / "command_fuzz_arm.yaml";
  std::ifstream in(wbi::test::source_dir() / "deploy" / "robots" / "arm.yaml");
  std::ofstream out(to);
  std::string line;
  while (std::getline(in, line)) {
    out << (line.rfind("urdf:", 0) == 0 ? "urdf: " + wbi::test::project_model("arm7.urdf").string()
                                        : line)
        << "\n";
  }
  return to;
}

TEST(CommandFuzz, RobotSurvivesCountsEverySampleAndObeysAGoodControllerAfterwards) {
  const auto file = wbi::test::binary_dir() / "tests" / "command_fuzz.yaml";
  std::ofstream(file) << "status_period_s: 0.05\ncomponents:\n"
                      << "  - name: arm\n    type: sim_robot\n    parameters:\n"
                      << "      robot: " << kRobot << "\n      config: " << arm_config().string()
                      << "\n      watchdog_timeout_s: 0.1\n";
  wbi::dds::Participant participant("command_fuzz");
  wbi::dds::Subscriber<ComponentStatus> status(participant, topics::kStatus, qos::kStatus);
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(participant, topics::sensors(kRobot),
                                                       qos::kStream);
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(participant, topics::commands(kRobot),
                                                          qos::kCommand);
  wbi::dds::Publisher<wbi::msg::ControlParameters> parameters(
      participant, topics::control_parameters(kRobot), qos::kCommand);
  wbi::test::ChildProcess host(wbi::test::binary_dir() / "bin" / "wbi_host", {file.string()});
  ASSERT_TRUE(commands.wait_for_subscribers(1, 30s)) << host.output();
  ASSERT_TRUE(parameters.wait_for_subscribers(1, 30s)) << host.output();
  wbi::dds::Received<wbi::msg::SensorSample> sample;
  ASSERT_TRUE(sensors.wait_newer(sample, 0, 30s)) << host.output();
  const auto home = sample.sample.encoder_position();

  // 3 s at 1 kHz: a command every tick, parameters every fourth.
  const std::uint64_t seed = 26;
  Fuzzer fuzz(seed);
  std::uint64_t valid_commands = 0, bad_commands = 0, valid_parameters = 0, bad_parameters = 0;
  auto next = std::chrono::steady_clock::now();
  for (int k = 0; k < 3000; ++k) {
    next += 1ms;  // pacing, not synchronisation
    std::this_thread::sleep_until(next);
    bool valid = false;
    if (k % 4 == 3) {
      parameters.publish(fuzz.parameters(valid));
      (valid ? valid_parameters : bad_parameters) += 1;
    } else {
      commands.publish(fuzz.command(valid));
      (valid ? valid_commands : bad_commands) += 1;
    }
  }
  const std::uint64_t sent = valid_commands + bad_commands + valid_parameters + bad_parameters;

  // The robot's count settles once every sample it will get is handled.
  auto counted = [](const ComponentStatus& s) {
    return counter(s, "accepted_commands") + counter(s, "rejected_commands") +
           counter(s, "accepted_parameters") + counter(s, "rejected_parameters");
  };
  wbi::dds::Received<ComponentStatus> got;
  std::uint64_t last = 0;
  int stable = 0;
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (std::chrono::steady_clock::now() < deadline && stable < 5) {
    if (status.wait_newer(got, got.count, 1s) && got.sample.instance().to_string() == "arm") {
      const auto now = counted(got.sample);
      stable = now == last ? stable + 1 : 0;
      last = now;
      if (now == sent) {
        break;
      }
    }
  }
  ASSERT_TRUE(host.running()) << "the robot died under the fuzz:\n" << host.output();
  const ComponentStatus s = got.sample;
  std::cout << "[measured] fuzz seed " << seed << ": sent " << sent << " (commands "
            << valid_commands << " valid, " << bad_commands << " bad; parameters "
            << valid_parameters << " valid, " << bad_parameters << " bad); robot counted "
            << counted(s) << ": commands " << counter(s, "accepted_commands") << " accepted, "
            << counter(s, "rejected_commands") << " rejected; parameters "
            << counter(s, "accepted_parameters") << " accepted, "
            << counter(s, "rejected_parameters") << " rejected\n";
  // Every sample that arrived is counted, in its class; none was invented.
  EXPECT_LE(counter(s, "accepted_commands"), valid_commands);
  EXPECT_LE(counter(s, "rejected_commands"), bad_commands);
  EXPECT_LE(counter(s, "accepted_parameters"), valid_parameters);
  EXPECT_LE(counter(s, "rejected_parameters"), bad_parameters);
  EXPECT_GE(counted(s), sent / 2) << "most samples arrive on one host (all, unless the robot lags)";
  if (counted(s) == sent) {  // nothing lost on the way: exactly as built
    EXPECT_EQ(counter(s, "accepted_commands"), valid_commands);
    EXPECT_EQ(counter(s, "rejected_commands"), bad_commands);
    EXPECT_EQ(counter(s, "accepted_parameters"), valid_parameters);
    EXPECT_EQ(counter(s, "rejected_parameters"), bad_parameters);
  }
  std::uint64_t per_sender = 0;
  for (const auto& c : s.counters()) {
    if (c.name().to_string().rfind("rejected_from/", 0) == 0) {
      per_sender += c.value();
    }
  }
  EXPECT_EQ(per_sender, counter(s, "rejected_commands") + counter(s, "rejected_parameters"));

  // A good controller: sane gains and speed, then the start posture in POSITION.
  wbi::msg::ControlParameters gains;
  gains.header().robot(kRobot);
  gains.controller("good");
  wbi::msg::ActuatorCommand command;
  command.header().robot(kRobot);
  command.controller("good");
  for (unsigned short j = 0; j < kJoints; ++j) {
    gains.joints().push_back(j);
    command.joints().push_back(j);
    command.modes().push_back(wbi::msg::POSITION);
    command.references().push_back(home[j]);
  }
  // the robot's default gains (kp = 10 × effort limit, kd = kp / 200 s)
  wbi::dds::Subscriber<wbi::msg::RobotDescription> description(
      participant, topics::description(kRobot), qos::kLatched);
  wbi::dds::Received<wbi::msg::RobotDescription> limits;
  ASSERT_TRUE(description.wait_newer(limits, 0, 10s));
  for (int j = 0; j < kJoints; ++j) {
    const double kp = 10.0 * limits.sample.joint_limits()[static_cast<std::size_t>(j)].effort_max();
    gains.kp().push_back(kp);
    gains.kd().push_back(kp / 200.0);
  }
  gains.ki(std::vector<double>(kJoints, 0.0));
  gains.reference_speed(std::vector<double>(kJoints, 2.0));
  const auto accepted = counter(s, "accepted_parameters");
  parameters.publish(gains);
  // applied before the command, which plans with the new speed (two topics: no order between them)
  const auto applied = std::chrono::steady_clock::now() + 10s;
  while (std::chrono::steady_clock::now() < applied &&
         !(status.wait_newer(got, got.count, 1s) && got.sample.instance().to_string() == "arm" &&
           counter(got.sample, "accepted_parameters") > accepted)) {
  }
  ASSERT_GT(counter(got.sample, "accepted_parameters"), accepted) << got.sample.last_error();
  commands.publish(command);
  double error = INFINITY;
  const auto settle = std::chrono::steady_clock::now() + 20s;
  while (std::chrono::steady_clock::now() < settle && error > 0.02) {
    if (sensors.wait_newer(sample, sample.count, 1s)) {
      error = 0.0;
      for (int j = 0; j < kJoints; ++j) {
        error = std::max(error, std::abs(sample.sample.encoder_position()[j] - home[j]));
      }
    }
  }
  EXPECT_LT(error, 0.02) << "the good controller's posture was not reached\n" << host.output();
  EXPECT_EQ(host.stop(), 0) << host.output();
  const std::string log = host.output();
  const auto lines = std::count(log.begin(), log.end(), '\n');
  std::cout << "[measured] the robot's log: " << lines << " lines for "
            << counter(s, "rejected_commands") + counter(s, "rejected_parameters")
            << " rejections\n";
  EXPECT_LT(lines, 400);  // one per (sender, kind), ≤ 64 kinds, summaries: not one per sample
}

}  // namespace
