// wbi_bench_bridge [--window S (8)] [--clients N (2)]
//
// The demo (deploy/demo.yaml: robot, estimator, model service, PD controller;
// four processes at 1 kHz) runs; an observer in this process measures its
// sensor-to-command latency (bench/control_latency/latency_observer.hpp) in
// windows of S seconds:
//   no bridge → `wbi bridge` with no client → N clients subscribed to every
//   channel (1 kHz sensors, state, commands…, 30 Hz transforms) → N clients on
//   the sensors, the state and the transforms only → no client → no bridge.
// With clients it also measures, in the clients, DDS arrival → WebSocket
// receipt of every sensor sample (the message's receive time, set when the
// bridge got the sample from DDS, against the system clock when the client has
// read it: arrival → send plus the loopback hop and the client's read), and
// the bridge process's CPU time (/proc/PID/stat), and the rate at which each
// client gets the 30 Hz transforms (test_bridge checks only that they are
// throttled, not how close to 30 Hz a loaded machine keeps them).
// The last line is one JSON object. Runs on WBI_DOMAIN_ID (default 79).
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "../common/percentile.hpp"
#include "latency_observer.hpp"
#include "launch_process.hpp"
#include "ws_test_client.hpp"

extern char** environ;

namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using wbi::bench::percentile;

const std::filesystem::path kSource = WBI_SOURCE_DIR;

std::uint64_t system_now_ns() {
  return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        std::chrono::system_clock::now().time_since_epoch())
                                        .count());
}

// `wbi bridge --port 0`, its output in a file; stopped with SIGINT.
class BridgeProcess {
 public:
  explicit BridgeProcess(const std::filesystem::path& log) : log_(log) {
    const auto wbi = std::filesystem::canonical("/proc/self/exe").parent_path() / "wbi";
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    std::vector<std::string> args{wbi.string(), "bridge", "--port", "0"};
    std::vector<char*> argv;
    for (auto& arg : args) {
      argv.push_back(arg.data());
    }
    argv.push_back(nullptr);
    if (posix_spawn(&pid_, wbi.c_str(), &actions, nullptr, argv.data(), environ) != 0) {
      throw std::runtime_error("cannot start " + wbi.string());
    }
    posix_spawn_file_actions_destroy(&actions);
  }
  ~BridgeProcess() {
    kill(pid_, SIGINT);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  // The port once the bridge has made the robot's transforms (it is then serving).
  std::uint16_t wait_ready(std::chrono::seconds timeout) const {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      std::ifstream in(log_);
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      std::smatch match;
      if (text.find("transforms of arm") != std::string::npos &&
          std::regex_search(text, match, std::regex(R"(ws://127\.0\.0\.1:(\d+))"))) {
        return static_cast<std::uint16_t>(std::stoi(match[1]));
      }
      std::this_thread::sleep_for(100ms);  // polls a file: no event to wait on
    }
    throw std::runtime_error("the bridge did not get ready; its log: " + log_.string());
  }
  // utime + stime [s] so far.
  double cpu_seconds() const {
    std::ifstream in("/proc/" + std::to_string(pid_) + "/stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::istringstream fields(text.substr(text.rfind(')') + 2));
    std::string field;
    double ticks = 0;
    for (int i = 3; i <= 15 && fields >> field; ++i) {
      if (i == 14 || i == 15) {
        ticks += std::stod(field);
      }
    }
    return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
  }

 private:
  pid_t pid_ = -1;
  std::filesystem::path log_;
};

// A client subscribed to every channel, reading on its own thread; for the
// sensors it keeps arrival → receipt latencies.
class ReadingClient {
 public:
  // topics: the channels to subscribe to; empty: all.
  ReadingClient(std::uint16_t port, const std::set<std::string>& topics) : client_(port) {
    client_.next_json("serverInfo", 5s);
    const auto advertise = client_.next_json("advertise", 5s);
    if (!advertise) {
      throw std::runtime_error("no advertisement");
    }
    json subscriptions = json::array();
    std::uint32_t id = 1;
    for (const auto& channel : (*advertise)["channels"]) {
      if (!topics.empty() && topics.count(channel["topic"]) == 0) {
        continue;
      }
      if (channel["topic"] == "wbi/arm/sensors") {
        sensors_ = id;
      }
      if (channel["topic"] == "wbi/arm/transforms") {
        transforms_ = id;
      }
      subscriptions.push_back({{"id", id++}, {"channelId", channel["id"]}});
    }
    client_.send_json({{"op", "subscribe"}, {"subscriptions", subscriptions}});
    latencies_us_.reserve(200000);
    thread_ = std::thread([this] { read(); });
  }
  ~ReadingClient() {
    stop_ = true;
    thread_.join();
  }
  std::vector<double> latencies_us() {
    std::lock_guard lock(mutex_);
    return latencies_us_;
  }
  std::uint64_t messages() const { return messages_; }
  std::uint64_t transforms() const { return transform_messages_; }

 private:
  void read() {
    while (!stop_) {
      const auto frame = client_.read(2s);
      if (!frame) {
        return;
      }
      ++messages_;
      if (!frame->text && frame->subscription() == transforms_) {
        ++transform_messages_;
      }
      if (!frame->text && frame->subscription() == sensors_) {
        const double us = 1e-3 * static_cast<double>(system_now_ns() - frame->receive_ns());
        std::lock_guard lock(mutex_);
        latencies_us_.push_back(us);
      }
    }
  }
  wbi::test::WsTestClient client_;
  std::uint32_t sensors_ = 0;
  std::uint32_t transforms_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<std::uint64_t> messages_{0};
  std::atomic<std::uint64_t> transform_messages_{0};
  std::mutex mutex_;
  std::vector<double> latencies_us_;
  std::thread thread_;
};

json summary(const std::vector<double>& values) {
  return {{"n", values.size()},
          {"p50_us", percentile(values, 0.5)},
          {"p99_us", percentile(values, 0.99)},
          {"max_us", values.empty() ? 0.0 : *std::max_element(values.begin(), values.end())}};
}

}  // namespace

int main(int argc, char** argv) {
  double window_s = 8.0;
  int clients = 2;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--window" && i + 1 < argc) {
      window_s = std::stod(argv[++i]);
    } else if (arg == "--clients" && i + 1 < argc) {
      clients = std::stoi(argv[++i]);
    } else {
      std::cout << "usage: wbi_bench_bridge [--window S (8)] [--clients N (2)]\n";
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  setenv("WBI_DOMAIN_ID", std::getenv("WBI_DOMAIN_ID") ? std::getenv("WBI_DOMAIN_ID") : "79", 1);
  const auto scratch =
      std::filesystem::temp_directory_path() / ("wbi_bench_bridge_" + std::to_string(getpid()));
  std::filesystem::create_directories(scratch);

  wbi::dds::Participant participant("wbi_bench_bridge");
  wbi::bench::LatencyObserver observer(participant, "arm", "pd_gravity", 1u << 20);
  wbi::bench::LaunchProcess demo(kSource / "deploy" / "demo.yaml", 6 * window_s + 60,
                                 scratch / "demo.log");
  const auto started = std::chrono::steady_clock::now();
  while (observer.result().latencies_us.size() < 2000) {  // the loop runs: 2 s of commands seen
    if (std::chrono::steady_clock::now() - started > 60s) {
      std::cerr << "the demo did not start; its log: " << (scratch / "demo.log") << "\n";
      return 1;
    }
    std::this_thread::sleep_for(100ms);
  }
  std::map<std::string, std::vector<double>> loop;
  const auto window = [&](const std::string& name) {
    const auto from = observer.result().latencies_us.size();
    std::this_thread::sleep_for(std::chrono::duration<double>(window_s));  // the measurement window
    const auto all = observer.result().latencies_us;
    loop[name].insert(loop[name].end(), all.begin() + static_cast<std::ptrdiff_t>(from), all.end());
  };

  window("no_bridge");
  json out;
  {
    BridgeProcess bridge(scratch / "bridge.log");
    const auto port = bridge.wait_ready(60s);
    window("bridge_no_client");
    // N clients on every channel: the loop's latency, the forwarding latency, the CPU.
    // Then N clients on the sensors, the state and the transforms: the CPU.
    for (const bool every_channel : {true, false}) {
      const std::set<std::string> topics =
          every_channel
              ? std::set<std::string>{}
              : std::set<std::string>{"wbi/arm/sensors", "wbi/arm/state", "wbi/arm/transforms"};
      const std::string key =
          every_channel ? "clients_on_every_channel" : "clients_on_sensors_state_transforms";
      std::vector<std::unique_ptr<ReadingClient>> readers;
      for (int c = 0; c < clients; ++c) {
        readers.push_back(std::make_unique<ReadingClient>(port, topics));
      }
      std::this_thread::sleep_for(1s);  // let the subscriptions settle before measuring
      const double cpu_before = bridge.cpu_seconds();
      const auto wall_before = std::chrono::steady_clock::now();
      std::uint64_t messages_before = 0;
      std::uint64_t transforms_before = 0;
      for (auto& reader : readers) {
        messages_before += reader->messages();
        transforms_before += reader->transforms();
      }
      window(every_channel ? "bridge_with_clients" : "bridge_with_clients_on_three_channels");
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_before).count();
      std::uint64_t messages = 0;
      std::uint64_t transforms = 0;
      std::vector<double> forward;
      for (auto& reader : readers) {
        messages += reader->messages();
        transforms += reader->transforms();
        const auto latencies = reader->latencies_us();
        forward.insert(forward.end(), latencies.begin(), latencies.end());
      }
      out[key]["bridge_cpu_percent_of_a_core"] = 100.0 * (bridge.cpu_seconds() - cpu_before) / wall;
      out[key]["messages_per_s_to_all_clients"] =
          static_cast<double>(messages - messages_before) / wall;
      out[key]["transforms_per_s_per_client"] =
          static_cast<double>(transforms - transforms_before) / wall / clients;
      out[key]["sensors_arrival_to_client_receipt"] = summary(forward);
    }
    window("bridge_no_client");
  }
  window("no_bridge");
  std::filesystem::remove_all(scratch);

  out["clients"] = clients;
  out["window_s"] = window_s;
  for (const auto& [name, values] : loop) {
    out["sensor_to_command"][name] = summary(values);
  }
  const double base = out["sensor_to_command"]["no_bridge"]["p99_us"];
  const double idle = out["sensor_to_command"]["bridge_no_client"]["p99_us"];
  const double busy = out["sensor_to_command"]["bridge_with_clients"]["p99_us"];
  out["p99_with_clients_over_no_bridge"] = base > 0 ? busy / base : 0.0;
  out["p99_with_clients_over_idle_bridge"] = idle > 0 ? busy / idle : 0.0;
  std::cout << out.dump() << std::endl;
  return 0;
}
