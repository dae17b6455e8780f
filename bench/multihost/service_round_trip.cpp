// wbi_bench_multihost_service --deploy FILE [--identity NAME] [--robot NAME]
//                             [--urdf FILE] [--calls N] [--discovery-rounds N]
//
// Round trips to a model service that runs elsewhere (another host: run.sh
// starts it with `wbi_host FILE --process model_service` in the other network
// namespace), with this participant placed as the deploy file says (network,
// security). Measures
//   discovery: a fresh participant and client until connected to the running
//              service (authentication and key exchange included when secured);
//   round trip: gravity forces G(q) at random q, one call at a time.
// Prints a summary, then one JSON object as the last line.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <wbi/dds/client.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/model/urdf.hpp>

#include "../common/percentile.hpp"
#include "deploy_participant.hpp"
#include "tool_main.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::bench::percentile;
using wbi::msg::ModelReply;
using wbi::msg::ModelRequest;
using Clock = std::chrono::steady_clock;
using ModelClient = wbi::dds::Client<ModelRequest, ModelReply>;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Options {
  std::string deploy;
  std::string identity = "controller";  // may call the model service in the demo's permissions
  std::string robot = "arm";
  std::string urdf = (std::filesystem::path(WBI_SOURCE_DIR) / "models" / "arm7.urdf").string();
  long calls = 5000;
  int discovery_rounds = 5;
};

Options parse(int argc, char** argv) {
  Options options;
  const auto count = [](const std::string& option, const std::string& text) {
    return static_cast<long>(wbi::bench::number_option(
        option, text, "a whole count >= 1",
        [](double n) { return n >= 1 && n == std::floor(n) && n < 1e15; }));
  };
  wbi::bench::for_each_option(argc, argv, [&](const std::string& arg, const std::string& value) {
    if (arg == "--deploy") {
      options.deploy = value;
    } else if (arg == "--identity") {
      options.identity = value;
    } else if (arg == "--robot") {
      options.robot = value;
    } else if (arg == "--urdf") {
      options.urdf = value;
    } else if (arg == "--calls") {
      options.calls = count(arg, value);
    } else if (arg == "--discovery-rounds") {
      options.discovery_rounds = static_cast<int>(std::min(count(arg, value), 1000L));
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
  const auto placement =
      wbi::bench::deploy_participant_options(options.deploy, "bench_service", options.identity);
  const std::string service = wbi::dds::topics::model_service(options.robot);
  {
    // The service may still be starting: this first connection is not timed.
    wbi::dds::Participant probe(placement);
    ModelClient client(probe, service);
    if (!client.wait_connected(60s)) {
      throw std::runtime_error("no model service '" + service + "' within 60 s");
    }
  }
  std::vector<double> discovery_ms;
  for (int round = 0; round < options.discovery_rounds; ++round) {
    const auto start = Clock::now();
    wbi::dds::Participant fresh(placement);
    ModelClient client(fresh, service);
    if (!client.wait_connected(30s)) {
      throw std::runtime_error("discovery round " + std::to_string(round) + " took over 30 s");
    }
    discovery_ms.push_back(ms_since(start));
  }

  const auto model = wbi::model::load_urdf_file(options.urdf);
  wbi::dds::Participant participant(placement);
  ModelClient client(participant, service);
  if (!client.wait_connected(30s)) {
    throw std::runtime_error("not connected to '" + service + "'");
  }
  ModelRequest request;
  ModelReply reply;
  request.robot(options.robot);
  request.state().base_pose().orientation().w(1.0);
  request.state().gravity().z(-9.81);
  request.state().q().resize(static_cast<std::size_t>(model.n_joints));
  request.state().dq().resize(static_cast<std::size_t>(model.n_joints));
  request.operations().resize(1);
  request.operations()[0].operation(wbi::msg::GRAVITY_FORCES);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> joint(-1.0, 1.0);
  std::vector<double> rtt_us;
  std::vector<double> compute_us;
  rtt_us.reserve(static_cast<std::size_t>(options.calls));
  compute_us.reserve(static_cast<std::size_t>(options.calls));
  const long warmup = 200;
  for (long i = 0; i < warmup + options.calls; ++i) {
    for (auto& q : request.state().q()) {
      q = joint(rng);
    }
    const auto start = Clock::now();
    client.call(request, reply, 1s);
    const double rtt = 1e3 * ms_since(start);
    if (reply.error().size() != 0) {
      throw std::runtime_error("error reply: " + std::string(reply.error().c_str()));
    }
    if (i >= warmup) {
      rtt_us.push_back(rtt);
      compute_us.push_back(1e-3 * static_cast<double>(reply.compute_ns()));
    }
  }

  nlohmann::json out;
  out["deploy"] = options.deploy;
  out["secured"] = placement.security.enabled();
  out["calls"] = options.calls;
  out["rtt_p50_us"] = percentile(rtt_us, 0.50);
  out["rtt_p99_us"] = percentile(rtt_us, 0.99);
  out["rtt_max_us"] = percentile(rtt_us, 1.0);
  out["compute_p50_us"] = percentile(compute_us, 0.50);
  out["discovery_p50_ms"] = percentile(discovery_ms, 0.50);
  out["discovery_max_ms"] = percentile(discovery_ms, 1.0);
  std::cout << "gravity round trip: p50 " << out["rtt_p50_us"] << " us, p99 " << out["rtt_p99_us"]
            << " us (compute " << out["compute_p50_us"] << " us); discovery "
            << out["discovery_p50_ms"] << " ms median of " << options.discovery_rounds << "\n"
            << out.dump() << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const char* const usage =
      "usage: wbi_bench_multihost_service --deploy FILE [--identity NAME] [--robot NAME]\n"
      "         [--urdf FILE] [--calls N] [--discovery-rounds N]\n"
      "Model-service round trips and discovery time, placed as FILE says.\n";
  return wbi::bench::tool_main(argc, argv, "wbi_bench_multihost_service", usage, &parse, &run);
}
