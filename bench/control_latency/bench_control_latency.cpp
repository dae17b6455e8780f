// wbi_bench_control_latency [--duration S] [--ticks N] [--deploy FILE] [--skip-ticks]
//                           [--skip-chain] [--skip-demo]
//
// (a) Control tick: this process is the controller — PD + gravity through
//     the DDS whole-body interface, one tick = read the state estimate,
//     compute the gravity forces, send the torques — against the simulated
//     arm (real time, 1 kHz), the estimator and the model service in three
//     other processes (bench/control_latency/peers.yaml). N ticks at 1 kHz
//     with the local model, then N with the remote model: p50/p99 of a tick.
// (b) The demo, deploy/demo.yaml (robot, estimator, model service, controller
//     with the remote model; four processes, 1 kHz) for S seconds: the
//     controller's deadline misses (its loop's overruns, from its status on
//     wbi/status) and the sensor-to-command latency p50/p99 measured by an
//     observer participant in this process (latency_observer.hpp). --deploy
//     runs another deploy file with the same robot (arm) and controller
//     instance name (pd_gravity).
// (c) The raw chain, run just before (b) for as long: the same five DDS hops
//     (robot -> estimator -> controller -> model service -> controller ->
//     robot) between four processes that only relay (dds_chain_stage.cpp),
//     seen by the same observer. (b)'s latency over (c)'s is what the
//     components add to the transport.
//
// The last line is one JSON object. Runs on WBI_DOMAIN_ID (default 77 here,
// so that it does not meet a demo running on domain 0).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/dds_interface.hpp>

#include "latency_observer.hpp"
#include "launch_process.hpp"

#include "../common/percentile.hpp"

using wbi::bench::percentile;

namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

const std::filesystem::path kSource = WBI_SOURCE_DIR;
const std::vector<std::string> kJoints{"joint_1", "joint_2", "joint_3", "joint_4",
                                       "joint_5", "joint_6", "joint_7"};

struct Options {
  double duration_s = 60.0;
  int ticks = 5000;
  std::filesystem::path deploy = kSource / "deploy" / "demo.yaml";
  bool run_ticks = true;
  bool run_chain = true;
  bool run_demo = true;
};

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        throw std::invalid_argument(arg + " needs a value");
      }
      return argv[++i];
    };
    if (arg == "--duration") {
      options.duration_s = std::stod(value());
    } else if (arg == "--ticks") {
      options.ticks = std::stoi(value());
    } else if (arg == "--deploy") {
      options.deploy = std::filesystem::absolute(value());
    } else if (arg == "--skip-ticks") {
      options.run_ticks = false;
    } else if (arg == "--skip-chain") {
      options.run_chain = false;
    } else if (arg == "--skip-demo") {
      options.run_demo = false;
    } else if (arg == "--help" || arg == "-h") {
      std::cout
          << "usage: wbi_bench_control_latency [--duration S (60)] [--ticks N (5000)] "
             "[--deploy FILE (deploy/demo.yaml)] [--skip-ticks] [--skip-chain] [--skip-demo]\n";
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown option " + arg + " (see --help)");
    }
  }
  if (!(options.duration_s > 0.0) || options.ticks <= 0) {
    throw std::invalid_argument("--duration and --ticks must be > 0");
  }
  return options;
}

struct TickResult {
  std::vector<double> tick_us;
  std::uint64_t stale = 0;
};

// N control ticks at 1 kHz with the given model, timed one by one.
TickResult run_ticks(wbi::DdsInterfaceOptions::ModelSource source, int ticks) {
  wbi::DdsInterfaceOptions options;
  options.robot = "arm";
  options.controller = "bench";  // one name for both runs: the same owner of the joints
  options.urdf = (kSource / "models" / "arm7.urdf").string();
  options.model_source = source;
  options.max_age_s = 0.05;
  auto robot = wbi::make_dds_interface(options);
  robot->add_joints(kJoints);
  robot->init(60s);
  const int n = robot->dofs();
  Eigen::VectorXd target(n);
  target << 0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0;
  Eigen::MatrixXd M(6 + n, 6 + n);
  robot->mass_matrix(target, wbi::Transform::Identity(), M);
  const auto gains =  // the demo's: 5 Hz bandwidth
      wbi::controllers::PdGravityGains::from_inertia(M.bottomRightCorner(n, n), 5.0);
  wbi::controllers::PdGravity pd(*robot, gains, target);
  pd.start();

  TickResult result;
  result.tick_us.reserve(static_cast<std::size_t>(ticks));
  auto next = Clock::now();
  for (int k = 0; k < ticks; ++k) {
    next += 1ms;
    std::this_thread::sleep_until(next);  // the loop's period, not a synchronisation
    const auto start = Clock::now();
    try {
      pd.update(wbi::ReadMode::latest);
    } catch (const wbi::StaleDataError&) {
      ++result.stale;
      continue;
    }
    result.tick_us.push_back(1e-3 * static_cast<double>((Clock::now() - start).count()));
  }
  return result;
}

// A figure over no measurement is null in the JSON, never 0 (which would read
// as a perfect result).
nlohmann::json quantile_or_null(const std::vector<double>& values, double p) {
  return values.empty() ? nlohmann::json() : nlohmann::json(percentile(values, p));
}
nlohmann::json max_or_null(const std::vector<double>& values) {
  return values.empty() ? nlohmann::json()
                        : nlohmann::json(*std::max_element(values.begin(), values.end()));
}

nlohmann::json tick_summary(const TickResult& r) {
  return {{"p50_us", quantile_or_null(r.tick_us, 0.5)},
          {"p99_us", quantile_or_null(r.tick_us, 0.99)},
          {"max_us", max_or_null(r.tick_us)},
          {"ticks", r.tick_us.size()},
          {"stale", r.stale}};
}

std::string last_line_with(const std::string& text, const std::string& marker) {
  const auto at = text.rfind(marker);
  if (at == std::string::npos) {
    return "";
  }
  return text.substr(at, text.find('\n', at) - at);
}

// Sensor-to-command latency and its three parts, as keys PREFIXlatency_p50_us, ...
void put_latencies(const wbi::bench::LatencyObserver::Result& r, const std::string& prefix,
                   nlohmann::json& out) {
  out[prefix + "latency_p50_us"] = quantile_or_null(r.latencies_us, 0.5);
  out[prefix + "latency_p99_us"] = quantile_or_null(r.latencies_us, 0.99);
  out[prefix + "latency_max_us"] = max_or_null(r.latencies_us);
  out[prefix + "latency_samples"] = r.latencies_us.size();
  for (const auto& [key, values] : {std::pair{"sensor_to_state", &r.to_state_us},
                                    std::pair{"state_to_command", &r.to_command_us},
                                    std::pair{"command_delivery", &r.delivery_us}}) {
    out[prefix + key + "_p50_us"] = quantile_or_null(*values, 0.5);
    out[prefix + key + "_p99_us"] = quantile_or_null(*values, 0.99);
  }
}

std::size_t samples_for(double duration_s) {
  return static_cast<std::size_t>(duration_s * 1000.0 * 1.5) + 10000;
}

// (c): the four relay stages for `duration_s`, the robot started last.
wbi::bench::LatencyObserver::Result run_chain(double duration_s,
                                              const std::filesystem::path& logs) {
  wbi::dds::Participant participant("bench_observer");
  wbi::bench::LatencyObserver observer(participant, "chain", "pd_gravity", samples_for(duration_s));
  std::vector<std::unique_ptr<wbi::bench::LaunchProcess>> stages;
  for (const char* role : {"model_service", "controller", "estimator", "robot"}) {
    stages.push_back(std::make_unique<wbi::bench::LaunchProcess>(
        "wbi_bench_dds_chain_stage", std::vector<std::string>{"--role", role},
        logs / (std::string("wbi_bench_control_latency_chain_") + role + ".log")));
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(duration_s));  // the run's length
  stages.clear();                                                          // SIGTERM, each
  return observer.result();
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = parse(argc, argv);
    if (std::getenv("WBI_DOMAIN_ID") == nullptr) {
      setenv("WBI_DOMAIN_ID", "77", 1);
    }
    const auto logs = std::filesystem::temp_directory_path();
    nlohmann::json out;
    // The parts that measured nothing (a chain or demo that delivered no
    // command, a tick loop that never got a state): the run fails, exit 1.
    std::vector<std::string> measured_nothing;

    if (options.run_ticks) {
      std::cerr << "(a) control ticks against robot, estimator, model service processes...\n";
      wbi::bench::LaunchProcess peers(kSource / "bench" / "control_latency" / "peers.yaml", 3600.0,
                                      logs / "wbi_bench_control_latency_peers.log");
      const TickResult local =
          run_ticks(wbi::DdsInterfaceOptions::ModelSource::local, options.ticks);
      const TickResult remote =
          run_ticks(wbi::DdsInterfaceOptions::ModelSource::remote, options.ticks);
      peers.stop();
      out["tick_local"] = tick_summary(local);
      out["tick_remote"] = tick_summary(remote);
      out["tick_local_p50_us"] = out["tick_local"]["p50_us"];
      out["tick_local_p99_us"] = out["tick_local"]["p99_us"];
      out["tick_remote_p50_us"] = out["tick_remote"]["p50_us"];
      out["tick_remote_p99_us"] = out["tick_remote"]["p99_us"];
      for (const auto& [name, run] :
           {std::pair{"(a) local ticks", &local}, std::pair{"(a) remote ticks", &remote}}) {
        if (run->tick_us.empty()) {
          measured_nothing.emplace_back(name);
        }
      }
      std::cerr << "  tick local  " << out["tick_local"].dump() << "\n  tick remote "
                << out["tick_remote"].dump() << "\n";
    }

    if (options.run_chain) {
      std::cerr << "(c) the raw five-hop chain, " << options.duration_s << " s...\n";
      const auto chain = run_chain(options.duration_s, logs);
      put_latencies(chain, "chain_", out);
      std::cerr << "  chain p50 " << out["chain_latency_p50_us"] << " us, p99 "
                << out["chain_latency_p99_us"] << " us over " << chain.latencies_us.size()
                << " commands\n";
      if (chain.latencies_us.empty()) {
        std::cerr << "no command came through the chain: see "
                  << (logs / "wbi_bench_control_latency_chain_*.log").string() << "\n";
        measured_nothing.emplace_back("(c) the chain");
      }
    }

    if (options.run_demo) {
      std::cerr << "(b) " << options.deploy.string() << ", " << options.duration_s << " s...\n";
      wbi::dds::Participant participant("bench_observer");
      wbi::bench::LatencyObserver observer(participant, "arm", "pd_gravity",
                                           samples_for(options.duration_s));
      wbi::bench::LaunchProcess demo(options.deploy, options.duration_s,
                                     logs / "wbi_bench_control_latency_demo.log");
      // The launcher stops everything after the duration (start-up comes on top).
      const bool ended = demo.wait(std::chrono::milliseconds(
          static_cast<std::int64_t>(options.duration_s * 1000.0) + 120'000));
      demo.stop();
      const std::string log = demo.output();
      const auto r = observer.result();
      put_latencies(r, "", out);
      if (out.value("chain_latency_samples", 0U) > 0 && !r.latencies_us.empty()) {
        out["latency_p50_vs_chain"] =
            out["latency_p50_us"].get<double>() / out["chain_latency_p50_us"].get<double>();
        out["latency_p99_vs_chain"] =
            out["latency_p99_us"].get<double>() / out["chain_latency_p99_us"].get<double>();
      }
      // Commands that came more than one control period (1 ms) after their sensor sample.
      out["late_commands"] = std::count_if(r.latencies_us.begin(), r.latencies_us.end(),
                                           [](double us) { return us > 1000.0; });
      out["deadline_misses"] = r.overruns;
      out["ticks"] = r.ticks;
      out["deadline_miss_percent"] =
          r.ticks == 0 ? 0.0
                       : 100.0 * static_cast<double>(r.overruns) / static_cast<double>(r.ticks);
      out["sensor_samples"] = r.sensor_samples;
      out["commands"] = r.commands;
      out["unmatched_commands"] = r.unmatched_commands;
      out["duration_s"] = options.duration_s;
      out["deploy"] = options.deploy.string();
      out["demo_ended"] = ended;
      std::cerr << "  " << last_line_with(log, "stale cycles:") << "\n  "
                << last_line_with(log, "final max joint error:") << "\n";
      if (r.latencies_us.empty() || r.ticks == 0) {
        std::cerr << "no latency or status seen; the demo's output:\n" << log;
        measured_nothing.emplace_back("(b) the demo");
      }
    }
    out["measured_nothing"] = measured_nothing;
    std::cout << out.dump() << std::endl;
    if (!measured_nothing.empty()) {
      std::cerr << "wbi_bench_control_latency: measured nothing in";
      for (const auto& part : measured_nothing) {
        std::cerr << " " << part << (&part == &measured_nothing.back() ? "" : ",");
      }
      std::cerr << " on domain " << std::getenv("WBI_DOMAIN_ID") << " (the processes' logs are in "
                << logs.string() << ")\n";
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "wbi_bench_control_latency: " << e.what() << "\n";
    return 1;
  }
}
