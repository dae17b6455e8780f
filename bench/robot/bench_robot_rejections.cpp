// The robot's loop under a bad publisher (issue 26): the driver component
// (wbi::robot::register_driver) over a toy backend at 1 kHz on the runner's
// wall-clock period, a good controller streaming POSITION_DIRECT at 1 kHz,
// and — in the second phase — a publisher of malformed ActuatorCommand and
// ControlParameters samples at 1 kHz (wrong robot, mode 77, joint index out of
// range, NaN, sizes that disagree, negative gains). Prints, per phase, the
// ticks run and missed (overruns), the period's jitter and maximum, the cycle
// time and the rejections counted; the last line is one JSON object.
//
//   wbi_bench_robot_rejections [--duration S]   (default 5 s per phase)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <thread>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/robot/robot_driver.hpp>
#include <wbi/runtime/runner.hpp>

#include "two_joint_toy.hpp"

namespace {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;
constexpr const char* kRobot = "bench_rejections";

// The k-th malformed command: one of six kinds, in turn.
wbi::msg::ActuatorCommand bad_command(std::uint64_t k) {
  wbi::msg::ActuatorCommand c;
  c.header().robot(kRobot);
  c.header().seq(k);
  c.controller("bad");
  c.joints({0, 1});
  c.modes({wbi::msg::POSITION_DIRECT, wbi::msg::POSITION_DIRECT});
  c.references({0.1, 0.2});
  switch (k % 5) {
    case 0:
      c.header().robot("not-this-robot");
      break;
    case 1:
      c.modes()[1] = static_cast<wbi::msg::ControlMode>(77);
      break;
    case 2:
      c.joints()[1] = static_cast<unsigned short>(40 + k % 100);
      break;
    case 3:
      c.references()[0] = std::numeric_limits<double>::quiet_NaN();
      break;
    default:
      c.references().push_back(0.0);
      break;
  }
  return c;
}

struct Phase {
  wbi::runtime::LoopStats stats;
  std::uint64_t bad_sent = 0;
  std::uint64_t good_sent = 0;
};

Phase run(double duration_s, bool with_bad_publisher) {
  wbi::dds::Participant participant("bench_robot_rejections");
  wbi::runtime::SystemClock clock;
  wbi::runtime::Registry registry;
  wbi::robot::register_driver(registry, "toy_robot", [](const wbi::runtime::Parameters&) {
    return std::make_unique<wbi::test::TwoJointToyBackend>(kRobot);
  });
  wbi::runtime::RunnerOptions options;
  options.rate_hz = 1000.0;
  options.status_period_s = 0.5;
  wbi::runtime::ComponentRunner runner(
      registry.create("toy_robot"),
      wbi::runtime::ComponentContext{"robot", "toy_robot", &participant, &clock}, options);
  runner.configure(wbi::runtime::Parameters::from_string(std::string("robot: ") + kRobot + "\n"));

  wbi::dds::Participant controllers("bench_robot_rejections_controllers");
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(controllers, topics::commands(kRobot),
                                                          qos::kCommand);
  wbi::dds::Publisher<wbi::msg::ControlParameters> parameters(
      controllers, topics::control_parameters(kRobot), qos::kCommand);
  commands.wait_for_subscribers(1, 10s);
  parameters.wait_for_subscribers(1, 10s);
  runner.activate();

  wbi::msg::ActuatorCommand good;
  good.header().robot(kRobot);
  good.controller("good");
  good.joints({0, 1});
  good.modes({wbi::msg::POSITION_DIRECT, wbi::msg::POSITION_DIRECT});
  good.references({0.0, 0.0});
  wbi::msg::ControlParameters bad_gains;
  bad_gains.header().robot(kRobot);
  bad_gains.controller("bad");
  bad_gains.joints({0});
  bad_gains.kp({-1.0});

  Phase phase;
  const auto start = std::chrono::steady_clock::now();
  auto next = start;
  for (std::uint64_t k = 0;
       std::chrono::steady_clock::now() - start < std::chrono::duration<double>(duration_s); ++k) {
    next += 1ms;  // 1 kHz pacing (not synchronisation)
    std::this_thread::sleep_until(next);
    good.header().seq(k);
    good.references()[0] = 0.5 * std::sin(1e-3 * static_cast<double>(k));
    commands.publish(good);
    ++phase.good_sent;
    if (with_bad_publisher) {
      if (k % 10 == 9) {
        parameters.publish(bad_gains);
      } else {
        commands.publish(bad_command(k));
      }
      ++phase.bad_sent;
    }
  }
  phase.stats = runner.stats();
  runner.shutdown();
  return phase;
}

void print(const char* name, const Phase& p) {
  std::printf(
      "%-22s ticks %6llu  missed %4llu  period mean %.4f ms  jitter %.4f ms  max %.3f ms  "
      "cycle mean %.1f us  max %.1f us  good sent %llu  bad sent %llu\n",
      name, static_cast<unsigned long long>(p.stats.iterations),
      static_cast<unsigned long long>(p.stats.overruns), p.stats.period_mean_s * 1e3,
      p.stats.period_jitter_s * 1e3, p.stats.period_max_s * 1e3, p.stats.cycle_mean_s * 1e6,
      p.stats.cycle_max_s * 1e6, static_cast<unsigned long long>(p.good_sent),
      static_cast<unsigned long long>(p.bad_sent));
}

}  // namespace

int main(int argc, char** argv) {
  double duration_s = 5.0;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--duration") == 0 && i + 1 < argc) {
      duration_s = std::stod(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: wbi_bench_robot_rejections [--duration S]\n");
      return std::strcmp(argv[i], "--help") == 0 ? 0 : 1;
    }
  }
  const Phase quiet = run(duration_s, false);
  const Phase attacked = run(duration_s, true);
  print("good controller only", quiet);
  print("+ bad publisher 1 kHz", attacked);
  std::printf(
      "{\"duration_s\": %g, \"ticks\": %llu, \"missed\": %llu, \"jitter_ms\": %.4f, "
      "\"ticks_bad\": %llu, \"missed_bad\": %llu, \"jitter_bad_ms\": %.4f, \"bad_sent\": %llu}\n",
      duration_s, static_cast<unsigned long long>(quiet.stats.iterations),
      static_cast<unsigned long long>(quiet.stats.overruns), quiet.stats.period_jitter_s * 1e3,
      static_cast<unsigned long long>(attacked.stats.iterations),
      static_cast<unsigned long long>(attacked.stats.overruns),
      attacked.stats.period_jitter_s * 1e3, static_cast<unsigned long long>(attacked.bad_sent));
  return 0;
}
