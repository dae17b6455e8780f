// wbi_bench_service [--json] [--calls N] [--model URDF]
//
// Round trips to the model service in a second process (this program again,
// in --serve mode, running the model-service component as wbi_host does) for
//   (a) gravity forces G(q), and
//   (b) M + h + four frame Jacobians,
// against a raw DDS ping-pong of the same payload sizes (ModelRequest out,
// ModelReply back, plain Publisher/Subscriber, no request/reply logic) between
// the same two processes. Also: discovery (a new participant + client until
// connected to the running service) and the server-side compute time.
// Model: ../shared/models/iCubGenova09/model.urdf when present, else
// models/humanoid.urdf. With --json the last line is one JSON object.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <pthread.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <wbi/dds/client.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/model/urdf.hpp>
#include <wbi/model_service/component.hpp>
#include <wbi/runtime/runner.hpp>

#include "../common/percentile.hpp"

using wbi::bench::percentile;

extern char** environ;

namespace {

using namespace std::chrono_literals;
using wbi::msg::ModelReply;
using wbi::msg::ModelRequest;
using Clock = std::chrono::steady_clock;

const std::string kRobot = "bench";
const std::string kPing = "wbi/bench/ping";
const std::string kPong = "wbi/bench/pong";

double us_since(Clock::time_point start) {
  return 1e-3 *
         static_cast<double>(
             std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count());
}

std::string default_model() {
  for (const auto& candidate :
       {std::filesystem::path(WBI_SOURCE_DIR) / ".." / "shared" / "models" / "iCubGenova09" /
            "model.urdf",
        std::filesystem::path(WBI_SOURCE_DIR) / "models" / "humanoid.urdf"}) {
    if (std::filesystem::exists(candidate)) {
      return std::filesystem::weakly_canonical(candidate).string();
    }
  }
  return "";
}

// ---- the second process ----
int serve(const std::string& urdf) {
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  wbi::dds::Participant participant("bench_service");
  wbi::runtime::SystemClock clock;
  wbi::runtime::ComponentRunner runner(
      std::make_unique<wbi::model_service::ModelServiceComponent>(),
      {"model", "model_service", &participant, &clock});
  runner.configure(wbi::runtime::Parameters::from_string("urdf: " + urdf + "\nrobot: " + kRobot));
  runner.activate();
  // Raw pong: answers every ping with a reply of the gravity reply's size.
  ModelReply pong;
  wbi::dds::Publisher<ModelReply> pong_writer(participant, kPong, wbi::dds::qos::kRequestReply);
  const auto model = wbi::model::load_urdf_file(urdf);
  pong.results().resize(1);
  pong.results()[0].rows(static_cast<std::uint32_t>(model.nv));
  pong.results()[0].cols(1);
  pong.results()[0].data().assign(static_cast<std::size_t>(model.nv), 1.0);
  wbi::dds::Subscriber<ModelRequest> ping_reader(
      participant, kPing, wbi::dds::qos::kRequestReply,
      [&](const ModelRequest& ping, const wbi::dds::detail::SampleInfo&) {
        pong.client_id(ping.client_id());
        pong.seq(ping.seq());
        pong_writer.publish(pong);
      });
  std::cout << "serve: ready" << std::endl;
  int signal_number = 0;
  sigwait(&signals, &signal_number);
  return 0;
}

// ---- the measuring process ----
struct Child {
  pid_t pid = -1;
  ~Child() {
    if (pid > 0) {
      kill(pid, SIGTERM);
      int status = 0;
      waitpid(pid, &status, 0);
    }
  }
};

// One kind of call, reused every round: its request and reply buffers.
struct Call {
  std::string name;  // for error messages
  ModelRequest request;
  ModelReply reply;
  std::vector<double> rtt_us;
  std::vector<double> compute_us;
};

void prepare(Call& call, const wbi::model::Model& model,
             const std::vector<wbi::msg::ModelOperation>& operations,
             const std::vector<std::string>& frames, long calls) {
  auto& request = call.request;
  request.robot(kRobot);
  request.state().base_pose().orientation().w(1.0);
  request.state().gravity().z(-9.81);
  request.state().q().resize(static_cast<std::size_t>(model.n_joints));
  request.state().dq().resize(static_cast<std::size_t>(model.n_joints));
  request.operations().resize(operations.size());
  std::size_t next_frame = 0;
  for (std::size_t i = 0; i < operations.size(); ++i) {
    request.operations()[i].operation(operations[i]);
    if (operations[i] == wbi::msg::JACOBIAN) {
      request.operations()[i].frame(frames[next_frame++ % frames.size()]);
    }
  }
  call.rtt_us.reserve(static_cast<std::size_t>(calls));
  call.compute_us.reserve(static_cast<std::size_t>(calls));
}

void service_call(wbi::dds::Client<ModelRequest, ModelReply>& client, Call& call, std::mt19937& rng,
                  bool record) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t k = 0; k < call.request.state().q().size(); ++k) {
    call.request.state().q()[k] = u(rng);
    call.request.state().dq()[k] = u(rng);
  }
  const auto start = Clock::now();
  try {
    client.call(call.request, call.reply, 1s);
  } catch (const wbi::dds::CallError& error) {
    throw std::runtime_error(call.name + ": " + error.what());
  }
  const double rtt = us_since(start);
  if (call.reply.error().size() != 0) {
    throw std::runtime_error(call.name + ": error reply: " + call.reply.error().c_str());
  }
  if (record) {
    call.rtt_us.push_back(rtt);
    call.compute_us.push_back(1e-3 * static_cast<double>(call.reply.compute_ns()));
  }
}

// Raw ping-pong: a ModelRequest of the gravity request's size out, a
// ModelReply of the gravity reply's size back, plain publisher/subscriber.
struct Raw {
  wbi::dds::Publisher<ModelRequest> ping;
  wbi::dds::Subscriber<ModelReply> pong;
  ModelRequest request;
  wbi::dds::Received<ModelReply> got;
  std::uint64_t received = 0;
  std::vector<double> rtt_us;
  // From the DDS thread's take (the pong's received_ns) to this thread running
  // again: the cost of handing a sample from the listener to a waiting thread.
  std::vector<double> handoff_us;

  // Pings sent again for want of a pong (the profile may be best effort).
  long resent = 0;

  Raw(wbi::dds::Participant& participant, const Call& gravity, long calls)
      : ping(participant, kPing, wbi::dds::qos::kRequestReply),
        pong(participant, kPong, wbi::dds::qos::kRequestReply),
        request(gravity.request) {
    if (!ping.wait_for_subscribers(1, 10s) || !pong.wait_for_publishers(1, 10s)) {
      throw std::runtime_error("raw ping-pong: no peer");
    }
    request.client_id("raw");
    round_trip(false);  // until the peer has matched us too
    resent = 0;
    rtt_us.reserve(static_cast<std::size_t>(calls));
    handoff_us.reserve(static_cast<std::size_t>(calls));
  }

  void round_trip(bool record) {
    request.seq(request.seq() + 1);
    const auto start = Clock::now();
    ping.publish(request);
    int tries = 1;
    do {
      if (!pong.wait_newer(got, received, 20ms)) {
        if (++tries > 100) {
          throw std::runtime_error("raw ping-pong: no pong for ping " +
                                   std::to_string(request.seq()));
        }
        ping.publish(request);
        ++resent;
        continue;
      }
      received = got.count;
    } while (got.sample.seq() != request.seq());
    const std::int64_t resumed_ns = wbi::dds::detail::steady_now_ns();
    if (record) {
      rtt_us.push_back(us_since(start));
      handoff_us.push_back(1e-3 * static_cast<double>(resumed_ns - got.received_ns));
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  long calls = 5000;
  std::string urdf = default_model();
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--serve" && i + 1 < argc) {
      return serve(argv[i + 1]);
    } else if (arg == "--json") {
      json = true;
    } else if (arg == "--calls" && i + 1 < argc) {
      calls = std::atol(argv[++i]);
    } else if (arg == "--model" && i + 1 < argc) {
      urdf = argv[++i];
    } else {
      std::cout << "usage: wbi_bench_service [--json] [--calls N] [--model URDF]\n"
                   "Round trips to the model service in a second process vs a raw DDS ping-pong.\n";
      return arg == "--help" || arg == "-h" ? 0 : 1;
    }
  }
  try {
    if (urdf.empty()) {
      throw std::runtime_error("no model found; pass --model URDF");
    }
    // A domain of our own unless one is given, so other processes on the host do not interfere.
    if (std::getenv("WBI_DOMAIN_ID") == nullptr) {
      setenv("WBI_DOMAIN_ID", std::to_string(200 + getpid() % 30).c_str(), 1);
    }
    const auto model = wbi::model::load_urdf_file(urdf);
    std::vector<std::string> frames;
    for (const char* name : {"l_sole", "r_sole", "l_hand", "r_hand"}) {
      if (model.has_frame(name)) {
        frames.emplace_back(name);
      }
    }
    for (int i = model.n_frames() - 1; frames.size() < 4 && i >= 0; --i) {
      frames.push_back(model.frame_name[static_cast<std::size_t>(i)]);
    }

    Child child;
    std::vector<std::string> args = {argv[0], "--serve", urdf};
    std::vector<char*> child_argv;
    for (auto& a : args) {
      child_argv.push_back(a.data());
    }
    child_argv.push_back(nullptr);
    if (posix_spawn(&child.pid, "/proc/self/exe", nullptr, nullptr, child_argv.data(), environ) !=
        0) {
      throw std::runtime_error("cannot start the service process");
    }

    // Discovery: a fresh participant and client each time, until connected.
    std::vector<double> discovery_ms;
    {
      wbi::dds::Participant first("bench_probe");
      wbi::dds::Client<ModelRequest, ModelReply> probe(first,
                                                       wbi::dds::topics::model_service(kRobot));
      if (!probe.wait_connected(30s)) {
        throw std::runtime_error("the service process did not come up within 30 s");
      }
    }
    for (int round = 0; round < 5; ++round) {
      const auto start = Clock::now();
      wbi::dds::Participant fresh("bench_discovery");
      wbi::dds::Client<ModelRequest, ModelReply> client(fresh,
                                                        wbi::dds::topics::model_service(kRobot));
      if (!client.wait_connected(10s)) {
        throw std::runtime_error("discovery took more than 10 s");
      }
      discovery_ms.push_back(1e-3 * us_since(start));
    }

    std::mt19937 rng(1);
    std::vector<double> raw_rtt_us;
    std::vector<double> raw_handoff_us;
    long raw_resent = 0;
    long rpc_resent = 0;
    wbi::dds::Participant participant("bench");
    Call a;
    Call b;
    a.name = "(a) gravity";
    b.name = "(b) M + h + 4 J";
    prepare(a, model, {wbi::msg::GRAVITY_FORCES}, frames, calls);
    prepare(b, model,
            {wbi::msg::MASS_MATRIX, wbi::msg::BIAS_FORCES, wbi::msg::JACOBIAN, wbi::msg::JACOBIAN,
             wbi::msg::JACOBIAN, wbi::msg::JACOBIAN},
            frames, calls);
    const long warmup = 200;
    {
      // (a) and the raw ping-pong interleaved, so that both see the same load
      // (this host is shared): a, raw, a, raw, ...
      wbi::dds::Client<ModelRequest, ModelReply> client(participant,
                                                        wbi::dds::topics::model_service(kRobot));
      if (!client.wait_connected(10s)) {
        throw std::runtime_error("not connected");
      }
      service_call(client, a, rng, false);  // the gravity request gets its final size
      Raw raw(participant, a, calls);
      for (long i = 0; i < warmup + calls; ++i) {
        service_call(client, a, rng, i >= warmup);
        raw.round_trip(i >= warmup);
      }
      raw_rtt_us = std::move(raw.rtt_us);
      raw_resent = raw.resent;
      rpc_resent = static_cast<long>(client.resent_requests());
      raw_handoff_us = std::move(raw.handoff_us);
    }
    {
      // (b) with a client of its own, once (a)'s is gone: every client's reply
      // reader receives every reply of the service (no content filter yet),
      // and a reply of another shape costs a deserialization that constructs
      // generated structs (see the report on idl/).
      wbi::dds::Client<ModelRequest, ModelReply> client(participant,
                                                        wbi::dds::topics::model_service(kRobot));
      if (!client.wait_connected(10s)) {
        throw std::runtime_error("not connected");
      }
      for (long i = 0; i < warmup + calls; ++i) {
        service_call(client, b, rng, i >= warmup);
      }
    }

    nlohmann::json out;
    out["model"] = urdf;
    out["n_joints"] = model.n_joints;
    out["calls"] = calls;
    out["rtt_p50_us"] = percentile(a.rtt_us, 0.50);
    out["rtt_p99_us"] = percentile(a.rtt_us, 0.99);
    out["compute_us"] = percentile(a.compute_us, 0.50);
    out["raw_p50_us"] = percentile(raw_rtt_us, 0.50);
    out["raw_p99_us"] = percentile(raw_rtt_us, 0.99);
    out["raw_handoff_p50_us"] = percentile(raw_handoff_us, 0.50);
    out["raw_resent"] = raw_resent;
    out["rtt_resent"] = rpc_resent;
    out["qos_file"] = std::getenv("WBI_QOS_FILE") != nullptr ? std::getenv("WBI_QOS_FILE") : "";
    out["transport"] =
        std::getenv("WBI_DDS_TRANSPORT") != nullptr ? std::getenv("WBI_DDS_TRANSPORT") : "udp";
    out["overhead_us"] =
        percentile(a.rtt_us, 0.50) - percentile(raw_rtt_us, 0.50) - percentile(a.compute_us, 0.50);
    out["b_rtt_p50_us"] = percentile(b.rtt_us, 0.50);
    out["b_rtt_p99_us"] = percentile(b.rtt_us, 0.99);
    out["b_compute_us"] = percentile(b.compute_us, 0.50);
    out["b_frames"] = frames;
    out["discovery_ms"] = percentile(discovery_ms, 0.50);
    out["discovery_max_ms"] = percentile(discovery_ms, 1.0);

    std::cout << std::fixed << std::setprecision(1);
    std::cout << "model " << urdf << " (" << model.n_joints << " joints), " << calls
              << " calls each\n"
              << "(a) gravity            rtt p50 " << out["rtt_p50_us"].get<double>() << " us  p99 "
              << out["rtt_p99_us"].get<double>() << " us  compute "
              << out["compute_us"].get<double>() << " us\n"
              << "(b) M + h + 4 J        rtt p50 " << out["b_rtt_p50_us"].get<double>()
              << " us  p99 " << out["b_rtt_p99_us"].get<double>() << " us  compute "
              << out["b_compute_us"].get<double>() << " us\n"
              << "raw ping-pong          rtt p50 " << out["raw_p50_us"].get<double>() << " us  p99 "
              << out["raw_p99_us"].get<double>() << " us  (listener to waiting thread "
              << out["raw_handoff_p50_us"].get<double>() << " us p50)\n"
              << "service overhead (a)   " << out["overhead_us"].get<double>()
              << " us  (rtt p50 - raw p50 - compute)\n"
              << "discovery              " << out["discovery_ms"].get<double>() << " ms median, "
              << out["discovery_max_ms"].get<double>() << " ms max\n";
    if (json) {
      std::cout << out.dump() << std::endl;
    }
    return 0;
  } catch (const std::exception& error) {
    std::cerr << "wbi_bench_service: " << error.what() << "\n";
    return 1;
  }
}
