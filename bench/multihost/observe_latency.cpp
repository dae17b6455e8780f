// wbi_bench_multihost_latency --deploy FILE [--identity NAME] [--robot NAME]
//                             [--controller INSTANCE] [--duration S] [--warmup S]
//
// Sensor-to-command latency of a demo that runs across hosts, observed on the
// robot's host (run.sh starts it in the robot's network namespace): the
// LatencyObserver of bench/control_latency, with this participant placed as
// the deploy file says (network, security; identity "observer" may only
// subscribe). A command's arrival here stands for its arrival at the robot.
// Both namespaces share the machine's clock, so arrival minus the sensor
// sample's source timestamp is one clock's difference.
// Waits for the controller's first command (60 s bound), skips --warmup
// seconds, then measures for --duration seconds. Prints a summary, then one
// JSON object (the keys of wbi_bench_control_latency's demo run) as the last line.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/percentile.hpp"
#include "../control_latency/latency_observer.hpp"
#include "deploy_participant.hpp"
#include "tool_main.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::bench::LatencyObserver;
using wbi::bench::percentile;

struct Options {
  std::string deploy;
  std::string identity = "observer";
  std::string robot = "arm";
  std::string controller = "pd_gravity";
  double duration_s = 20;
  double warmup_s = 2;
};

Options parse(int argc, char** argv) {
  Options options;
  const auto seconds = [](const std::string& option, const std::string& text, bool zero_allowed) {
    return zero_allowed ? wbi::bench::number_option(option, text, "seconds >= 0",
                                                    [](double s) { return s >= 0; })
                        : wbi::bench::number_option(option, text, "seconds > 0",
                                                    [](double s) { return s > 0; });
  };
  wbi::bench::for_each_option(argc, argv, [&](const std::string& arg, const std::string& value) {
    if (arg == "--deploy") {
      options.deploy = value;
    } else if (arg == "--identity") {
      options.identity = value;
    } else if (arg == "--robot") {
      options.robot = value;
    } else if (arg == "--controller") {
      options.controller = value;
    } else if (arg == "--duration") {
      options.duration_s = seconds(arg, value, false);
    } else if (arg == "--warmup") {
      options.warmup_s = seconds(arg, value, true);
    } else {
      throw std::invalid_argument("unknown option '" + arg + "'");
    }
  });
  if (options.deploy.empty()) {
    throw std::invalid_argument("--deploy FILE is required");
  }
  return options;
}

int run(const Options& options) {
  wbi::dds::Participant participant(
      wbi::bench::deploy_participant_options(options.deploy, "bench_latency", options.identity));
  // Room for every command at up to 2 kHz (the observer never grows its buffer).
  const auto capacity =
      static_cast<std::size_t>((options.warmup_s + options.duration_s + 5.0) * 2000.0);
  LatencyObserver observer(participant, options.robot, options.controller, capacity);
  // The observer has no wait: poll its counters, bounded.
  const auto first_deadline = std::chrono::steady_clock::now() + 60s;
  while (observer.result().commands == 0) {
    if (std::chrono::steady_clock::now() > first_deadline) {
      throw std::runtime_error("no command on " + options.robot + "'s command topic within 60 s");
    }
    std::this_thread::sleep_for(50ms);
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(options.warmup_s));
  // The loop rate is counted between two status reports of the controller: the
  // window starts once one came (1 s heartbeats, best effort: over a lossy link
  // none may have come within the warm-up; the rate was then printed as 0 Hz).
  const auto status_deadline = std::chrono::steady_clock::now() + 10s;
  while (observer.result().status_stamp_ns == 0) {
    if (std::chrono::steady_clock::now() > status_deadline) {
      throw std::runtime_error("no status of controller '" + options.controller +
                               "' on wbi/status within 10 s after its first command");
    }
    std::this_thread::sleep_for(50ms);
  }
  const LatencyObserver::Result before = observer.result();
  std::this_thread::sleep_for(std::chrono::duration<double>(options.duration_s));
  const LatencyObserver::Result after = observer.result();

  const std::vector<double> latencies(
      after.latencies_us.begin() + static_cast<std::ptrdiff_t>(before.latencies_us.size()),
      after.latencies_us.end());
  const auto ticks = after.ticks - before.ticks;
  const auto misses = after.overruns - before.overruns;
  nlohmann::json out;
  out["deploy"] = options.deploy;
  out["secured"] = participant.options().security.enabled();
  out["duration_s"] = options.duration_s;
  out["latency_p50_us"] = percentile(latencies, 0.50);
  out["latency_p99_us"] = percentile(latencies, 0.99);
  out["latency_max_us"] = percentile(latencies, 1.0);
  out["latency_samples"] = latencies.size();
  out["late_commands"] =
      std::count_if(latencies.begin(), latencies.end(), [](double us) { return us > 1000.0; });
  out["ticks"] = ticks;
  out["loop_rate_hz"] = LatencyObserver::loop_rate_hz(before, after);
  out["deadline_misses"] = misses;
  out["deadline_miss_percent"] =
      ticks > 0 ? 100.0 * static_cast<double>(misses) / static_cast<double>(ticks) : 0.0;
  out["sensor_samples"] = after.sensor_samples - before.sensor_samples;
  out["commands"] = after.commands - before.commands;
  out["unmatched_commands"] = after.unmatched_commands - before.unmatched_commands;
  if (latencies.empty() || ticks == 0) {
    throw std::runtime_error("no latency or no controller status seen in " +
                             std::to_string(options.duration_s) + " s: " + out.dump());
  }
  std::cout << "sensor to command: p50 " << out["latency_p50_us"] << " us, p99 "
            << out["latency_p99_us"] << " us, max " << out["latency_max_us"] << " us ("
            << latencies.size() << " commands); deadline misses " << misses << " of " << ticks
            << "\n"
            << out.dump() << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const char* const usage =
      "usage: wbi_bench_multihost_latency --deploy FILE [--identity NAME] [--robot NAME]\n"
      "         [--controller INSTANCE] [--duration S] [--warmup S]\n"
      "Sensor-to-command latency of a running demo, observed here, placed as FILE says.\n";
  return wbi::bench::tool_main(argc, argv, "wbi_bench_multihost_latency", usage, &parse, &run);
}
