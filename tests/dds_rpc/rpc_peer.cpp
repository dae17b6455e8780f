// Test helper process for the request/reply tests.
//   wbi_test_rpc_peer server SERVICE [--worker-thread]
//       answers the toy service (rpc_fixture.hpp) until SIGTERM/SIGINT;
//       prints "server: ready" once its endpoints exist.
//   wbi_test_rpc_peer client SERVICE CALLS SEED [TIMEOUT_MS]
//   wbi_test_rpc_peer latency SERVICE CALLS      (prints round-trip p50/p99)
//       waits (20 s at most) to be connected, makes CALLS calls with random
//       states, checks every reply, prints "client: ok CALLS" and exits 0, or
//       prints the first failure and exits 1.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <pthread.h>

#include <wbi/dds/client.hpp>
#include <wbi/dds/server.hpp>

#include "rpc_fixture.hpp"

namespace {

using namespace std::chrono_literals;
using Request = wbi::msg::ModelRequest;
using Reply = wbi::msg::ModelReply;

int run_server(const std::string& service, bool worker_thread) {
  // SIGTERM/SIGINT are taken by sigwait below; blocked before any DDS thread starts.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  wbi::dds::Participant participant("rpc_server");
  wbi::dds::ServerOptions options;
  options.handle_on_dds_thread = !worker_thread;
  wbi::dds::Server<Request, Reply> server(participant, service, wbi::test::toy_reply, options);
  std::cout << "server: ready" << std::endl;
  int signal_number = 0;
  sigwait(&signals, &signal_number);
  const auto stats = server.stats();
  // distinct: requests answered at least once (a resent copy may be answered again).
  std::cout << "server: received " << stats.received << " answered " << stats.answered
            << " distinct " << stats.answered - stats.answered_again << std::endl;
  return 0;
}

int run_client(const std::string& service, long calls, unsigned long seed, long timeout_ms) {
  const auto start = std::chrono::steady_clock::now();
  wbi::dds::Participant participant("rpc_client");
  wbi::dds::Client<Request, Reply> client(participant, service);
  if (!client.wait_connected(20s)) {
    std::cout << "client: not connected within 20 s" << std::endl;
    return 1;
  }
  std::cout << "client: connected in "
            << std::chrono::duration_cast<std::chrono::microseconds>(
                   std::chrono::steady_clock::now() - start)
                   .count()
            << " us" << std::endl;
  std::mt19937_64 rng(seed);
  Request request;
  Reply reply;
  for (long i = 0; i < calls; ++i) {
    wbi::test::random_request(rng, 1 + i % 40, request);
    try {
      client.call(request, reply, std::chrono::milliseconds(timeout_ms));
    } catch (const std::exception& error) {
      std::cout << "client: call " << i << " failed: " << error.what() << std::endl;
      return 1;
    }
    const std::string mismatch = wbi::test::toy_mismatch(request, reply);
    if (!mismatch.empty()) {
      std::cout << "client: call " << i << " wrong reply: " << mismatch << std::endl;
      return 1;
    }
  }
  std::cout << "client: ok " << calls << " dropped " << client.dropped_replies() << std::endl;
  return 0;
}

// Round-trip times of CALLS small calls, printed as p50/p99 [us].
int run_latency(const std::string& service, long calls) {
  wbi::dds::Participant participant("rpc_latency");
  wbi::dds::Client<Request, Reply> client(participant, service);
  if (!client.wait_connected(20s)) {
    return 1;
  }
  std::mt19937_64 rng(1);
  Request request;
  Reply reply;
  wbi::test::random_request(rng, 32, request);
  std::vector<double> us;
  us.reserve(static_cast<std::size_t>(calls));
  for (long i = 0; i < calls + 100; ++i) {
    const auto start = std::chrono::steady_clock::now();
    client.call(request, reply, 1s);
    const auto end = std::chrono::steady_clock::now();
    if (i >= 100) {
      us.push_back(1e-3 * static_cast<double>((end - start).count()));
    }
  }
  std::sort(us.begin(), us.end());
  std::cout << "latency: p50 " << us[us.size() / 2] << " us p99 " << us[us.size() * 99 / 100]
            << " us" << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string role = argc > 1 ? argv[1] : "";
  if (role == "server" && (argc == 3 || argc == 4)) {
    return run_server(argv[2], argc == 4 && std::string(argv[3]) == "--worker-thread");
  }
  if (role == "client" && (argc == 5 || argc == 6)) {
    return run_client(argv[2], std::atol(argv[3]), std::strtoul(argv[4], nullptr, 10),
                      argc == 6 ? std::atol(argv[5]) : 5000);
  }
  if (role == "latency" && argc == 4) {
    return run_latency(argv[2], std::atol(argv[3]));
  }
  std::cerr << "usage: wbi_test_rpc_peer server SERVICE [--worker-thread]\n"
               "       wbi_test_rpc_peer client SERVICE CALLS SEED [TIMEOUT_MS]\n";
  return 2;
}
