// Request/reply between participants of one process: correlation, deadlines
// and the known failure modes of request/reply over Fast DDS 2.x (lost first
// replies, replies before matching, clients leaving mid-call, a client started
// before its server).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <future>
#include <iostream>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <wbi/dds/client.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/server.hpp>
#include <wbi/dds/subscriber.hpp>

#include "rpc_fixture.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::dds::CallStatus;
using wbi::dds::Participant;
using wbi::test::eventually;
using Request = wbi::msg::ModelRequest;
using Reply = wbi::msg::ModelReply;
using Client = wbi::dds::Client<Request, Reply>;
using Server = wbi::dds::Server<Request, Reply>;
using Clock = std::chrono::steady_clock;

const std::string kService = "wbi/test/toy";

// Waits for pred, checking every millisecond, at most timeout.
// Handlers that block (the gates below) run on the server's worker thread, so
// that the DDS threads keep taking requests and match events meanwhile.
wbi::dds::ServerOptions worker_thread() {
  wbi::dds::ServerOptions options;
  options.handle_on_dds_thread = false;
  return options;
}

// A handler gate: requests block in the handler until opened.
class Gate {
 public:
  void open() {
    {
      std::lock_guard lock(mutex_);
      open_ = true;
    }
    changed_.notify_all();
  }
  void pass() {
    std::unique_lock lock(mutex_);
    ++waiting_;
    changed_.notify_all();
    changed_.wait_for(lock, 20s, [&] { return open_; });
  }
  bool wait_waiting(int count) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, 10s, [&] { return waiting_ >= count; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool open_ = false;
  int waiting_ = 0;
};

TEST(Rpc, CallReturnsTheReplyToItsOwnRequest) {
  Participant server_side("server");
  Participant client_side("client");
  Server server(server_side, kService, wbi::test::toy_reply);
  Client client(client_side, kService);
  EXPECT_EQ(std::string(client.client_id()).size(), 32u);
  std::mt19937_64 rng(1);
  Request request;
  Reply reply;
  for (int i = 0; i < 50; ++i) {
    wbi::test::random_request(rng, 1 + i, request);
    client.call(request, reply, 5s);
    EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
  }
  EXPECT_GE(server.stats().answered, 50u);  // resends may be answered twice
  EXPECT_EQ(server.clients(), 1);
}

// Connecting includes the probe's round trip (the server has matched the
// client too). Issue #4's "< 1 s" is a speed target, measured by
// wbi_bench_service (discovery_ms, discovery_max_ms), not checked here: the
// test checks that each new client connects (within the wait's 10 s) and is
// answered (seen: 1.2 s to connect at load 17).
TEST(Rpc, ANewClientConnectsToARunningServer) {
  Participant server_side("server");
  Server server(server_side, kService, wbi::test::toy_reply);
  for (int round = 0; round < 3; ++round) {
    const auto start = Clock::now();
    Participant client_side("client");
    Client client(client_side, kService);
    ASSERT_TRUE(client.wait_connected(10s));
    const auto elapsed = Clock::now() - start;
    std::cout << "connected in "
              << std::chrono::duration_cast<std::chrono::microseconds>(elapsed).count() << " us\n";
    Request request;
    Reply reply;
    const auto call_start = Clock::now();
    client.call(request, reply, 5s);
    EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
    std::cout
        << "first call in "
        << std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - call_start).count()
        << " us, held " << server.stats().held << "\n";
  }
}

TEST(Rpc, HandlingOnTheWorkerThreadGivesTheSameReplies) {
  Participant server_side("server");
  Participant client_side("client");
  wbi::dds::ServerOptions options;
  options.handle_on_dds_thread = false;
  Server server(server_side, kService, wbi::test::toy_reply, options);
  Client client(client_side, kService);
  std::mt19937_64 rng(2);
  Request request;
  Reply reply;
  for (int i = 0; i < 50; ++i) {
    wbi::test::random_request(rng, 7, request);
    client.call(request, reply, 5s);
    EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
  }
}

TEST(Rpc, NoServerIsATimeoutNamingTheServiceWithinTheDeadline) {
  Participant client_side("client");
  Client client(client_side, kService);
  Request request;
  Reply reply;
  const auto start = Clock::now();
  try {
    client.call(request, reply, 300ms);
    FAIL() << "call without a server returned";
  } catch (const wbi::dds::TimeoutError& error) {
    EXPECT_EQ(error.status(), CallStatus::not_connected);
    EXPECT_NE(std::string(error.what()).find("service 'wbi/test/toy'"), std::string::npos)
        << error.what();
    EXPECT_NE(std::string(error.what()).find("timed out after 300 ms"), std::string::npos)
        << error.what();
  }
  // Not before its deadline; and it returned (how soon after it on a loaded
  // machine is not this test's business: a bound that only rules out a hang).
  const auto elapsed = Clock::now() - start;
  EXPECT_GE(elapsed, 300ms);
  EXPECT_LT(elapsed, 300ms + 5s);
}

TEST(Rpc, ClientStartedBeforeTheServerGetsItsReply) {
  Participant client_side("client");
  Client client(client_side, kService);
  Request request;
  std::mt19937_64 rng(3);
  wbi::test::random_request(rng, 5, request);
  auto call = std::async(std::launch::async, [&] {
    Reply reply;
    const CallStatus status = client.try_call(request, reply, 10s);
    return std::make_pair(status, wbi::test::toy_mismatch(request, reply));
  });
  // The call is under way (waiting to be connected) before the server exists.
  ASSERT_EQ(call.wait_for(200ms), std::future_status::timeout);
  Participant server_side("server");
  Server server(server_side, kService, wbi::test::toy_reply);
  const auto [status, mismatch] = call.get();
  EXPECT_EQ(status, CallStatus::ok);
  EXPECT_EQ(mismatch, "");
}

TEST(Rpc, SlowReplyIsATimeoutAndTheLateReplyIsDropped) {
  Participant server_side("server");
  Participant client_side("client");
  Gate gate;
  Server server(
      server_side, kService,
      [&](const Request& request, Reply& reply) {
        if (request.seq() == 1) {
          gate.pass();
        }
        wbi::test::toy_reply(request, reply);
      },
      worker_thread());
  Client client(client_side, kService);
  std::mt19937_64 rng(4);
  Request request;
  Reply reply;
  wbi::test::random_request(rng, 3, request);
  const auto start = Clock::now();
  EXPECT_EQ(client.try_call(request, reply, 300ms), CallStatus::no_reply);
  EXPECT_LT(Clock::now() - start, 800ms);
  EXPECT_NE(wbi::dds::call_failure_message(kService, CallStatus::no_reply, 300ms, 1)
                .find("no reply to request 1 within 300 ms"),
            std::string::npos);
  gate.open();  // the reply to request 1 now arrives late: dropped by seq
  ASSERT_TRUE(eventually([&] { return client.dropped_replies() >= 1; }));
  wbi::test::random_request(rng, 3, request);
  EXPECT_EQ(client.try_call(request, reply, 5s), CallStatus::ok);
  EXPECT_EQ(request.seq(), 2u);
  EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
}

TEST(Rpc, HandlerErrorsComeBackAsErrorReplies) {
  Participant server_side("server");
  Participant client_side("client");
  Server server(server_side, kService, [](const Request& request, Reply&) {
    throw std::invalid_argument("unknown robot '" + std::string(request.robot().c_str()) + "'");
  });
  Client client(client_side, kService);
  Request request;
  request.robot("nobody");
  Reply reply;
  client.call(request, reply, 5s);
  EXPECT_STREQ(reply.error().c_str(), "unknown robot 'nobody'");
  EXPECT_EQ(reply.seq(), request.seq());
  EXPECT_EQ(server.stats().handler_errors, 1u);
}

// Lost first replies / replies before matching: a client sends once its reply
// reader has matched the server's reply writer, but the server's writer may
// not have matched that reader yet (discovery is not symmetric in time). Such a
// request is held and answered once the writer has matched, never written
// into the void. Fresh reply readers, each sending at once, hit that window
// in most rounds; every reply must arrive.
TEST(Rpc, RequestsAreHeldUntilTheClientsReplyReaderMatches) {
  Participant server_side("server");
  Server server(server_side, kService, wbi::test::toy_reply);
  constexpr std::uint64_t kRounds = 20;
  for (std::uint64_t round = 1; round <= kRounds; ++round) {
    Participant client_side("client");
    Client client(client_side, kService);
    Request request;
    Reply reply;
    const auto start = Clock::now();
    ASSERT_EQ(client.try_call(request, reply, 10s), CallStatus::ok) << "round " << round;
    EXPECT_LT(Clock::now() - start, 5s) << "round " << round << ": connecting and the first call";
  }
  const auto stats = server.stats();
  std::cout << stats.held << " of " << kRounds << " first requests were held\n";
  EXPECT_GE(stats.answered, kRounds);  // a request resent after 100 ms may be answered twice
  EXPECT_EQ(stats.dropped_unmatched, 0u);
}

TEST(Rpc, RequestsOfAReplyReaderThatNeverMatchesAreDroppedAfterTheWait) {
  Participant server_side("server");
  Participant sender_side("sender");
  wbi::dds::ServerOptions options;
  options.match_wait = 200ms;
  Server server(server_side, kService, wbi::test::toy_reply, options);
  wbi::dds::Publisher<Request> requests(sender_side, wbi::dds::topics::service_request(kService),
                                        wbi::dds::qos::kRequestReply);
  ASSERT_TRUE(requests.wait_for_subscribers(1, 10s));
  Request request;
  request.client_id("0123456789abcdef0123456789abcdef");  // nobody's reply reader
  request.seq(1);
  // Best effort: sent until the server has it (as a client would); later copies
  // of the held request are duplicates.
  ASSERT_TRUE(eventually([&] {
    requests.publish(request);
    return server.stats().received >= 1;
  }));
  EXPECT_TRUE(eventually([&] { return server.stats().dropped_unmatched == 1; }, 5s));
  EXPECT_EQ(server.stats().held, 1u);
  EXPECT_EQ(server.stats().received, 1u + server.stats().duplicates);
  EXPECT_EQ(server.stats().answered, 0u);
}

TEST(Rpc, RequestsOfAClientThatLeftMidCallAreDropped) {
  Participant server_side("server");
  Gate gate;
  Server server(
      server_side, kService,
      [&](const Request& request, Reply& reply) {
        if (request.robot() == "first") {
          gate.pass();
        }
        wbi::test::toy_reply(request, reply);
      },
      worker_thread());
  Participant stays_side("stays");
  Client stays(stays_side, kService);
  Request first;
  first.robot("first");
  ASSERT_TRUE(stays.wait_connected(10s));
  ASSERT_EQ(stays.send(first, 20s), CallStatus::ok);
  ASSERT_TRUE(gate.wait_waiting(1));  // the worker is busy with `first`
  {
    Participant leaves_side("leaves");
    Client leaves(leaves_side, kService);
    Request second;
    second.robot("second");
    ASSERT_TRUE(leaves.wait_connected(10s));
    ASSERT_EQ(leaves.send(second, 20s), CallStatus::ok);
    ASSERT_TRUE(eventually([&] { return server.stats().received == 2; }));
  }  // the client leaves while its request is queued
  ASSERT_TRUE(eventually([&] { return server.clients() == 1; }));
  gate.open();
  Reply reply;
  ASSERT_TRUE(eventually([&] { return stays.poll(reply) == CallStatus::ok; }));
  EXPECT_EQ(wbi::test::toy_mismatch(first, reply), "");
  ASSERT_TRUE(eventually([&] { return server.stats().dropped_gone == 1; }));
  // poll() may have resent `first` while its reply was on the way: answered again.
  EXPECT_EQ(server.stats().answered - server.stats().answered_again, 1u);
}

TEST(Rpc, ExpiredRequestsAreNotComputed) {
  Participant server_side("server");
  Participant client_side("client");
  Gate gate;
  std::atomic<int> computed{0};  // on the server's worker thread
  Server server(
      server_side, kService,
      [&](const Request& request, Reply& reply) {
        ++computed;
        if (request.seq() == 1) {
          gate.pass();
        }
        wbi::test::toy_reply(request, reply);
      },
      worker_thread());
  Client first(client_side, kService);
  Client second(client_side, kService);
  Request request;
  ASSERT_TRUE(first.wait_connected(10s));
  ASSERT_EQ(first.send(request, 20s), CallStatus::ok);
  ASSERT_TRUE(gate.wait_waiting(1));
  Reply reply;
  EXPECT_EQ(second.try_call(request, reply, 200ms), CallStatus::no_reply);
  // The client gave up at its deadline on the steady clock; the server judges
  // the request's deadline_ns on the system clock, which may lag by some
  // microseconds. Await it there as well.
  ASSERT_TRUE(
      eventually([&] { return wbi::dds::detail::system_now_ns() > request.deadline_ns(); }));
  gate.open();
  ASSERT_TRUE(eventually([&] { return first.poll(reply) == CallStatus::ok; }));
  // The expired request (and its resent copy) are dropped unseen by the handler.
  ASSERT_TRUE(eventually([&] { return server.stats().dropped_expired >= 1; }));
  // poll() may have resent `first` while its reply was on the way: answered
  // again, counted once that reply is written (a copy may still be running).
  const auto computed_once = [&] {
    return computed.load() - static_cast<int>(server.stats().answered_again) == 1;
  };
  EXPECT_TRUE(eventually(computed_once))
      << computed.load() << " computed, " << server.stats().answered_again << " answered again";
}

// A server that "loses" the first copy of every request and answers the second
// (a real participant with a plain subscriber and publisher, no Server).
// Connection probes (seq 0) are answered at once.
class ForgetfulServer {
 public:
  explicit ForgetfulServer(Participant& participant)
      : replies_(participant, wbi::dds::topics::service_reply(kService),
                 wbi::dds::qos::kRequestReply),
        requests_(participant, wbi::dds::topics::service_request(kService),
                  wbi::dds::qos::kRequestReply,
                  [this](const Request& request, const wbi::dds::detail::SampleInfo&) {
                    if (request.seq() != wbi::dds::kProbeSeq && request.seq() != seen_) {
                      seen_ = request.seq();  // the first copy: "lost"
                      return;
                    }
                    wbi::test::toy_reply(request, reply_);
                    reply_.client_id(request.client_id());
                    reply_.seq(request.seq());
                    replies_.publish(reply_);
                  }) {}

 private:
  std::uint64_t seen_ = 0;
  Reply reply_;
  wbi::dds::Publisher<Reply> replies_;
  wbi::dds::Subscriber<Request> requests_;
};

// A sample lost for good (best effort, or a KEEP_LAST history overflowing under
// load) is recovered by resending, in call()...
TEST(Rpc, ALostRequestIsResentWithinTheDeadline) {
  Participant server_side("server");
  Participant client_side("client");
  ForgetfulServer server(server_side);
  wbi::dds::ClientOptions options;
  options.resend_period = 50ms;
  Client client(client_side, kService, options);
  ASSERT_TRUE(client.wait_connected(10s));
  std::mt19937_64 rng(8);
  Request request;
  Reply reply;
  for (int i = 0; i < 3; ++i) {
    wbi::test::random_request(rng, 6, request);
    const auto start = Clock::now();
    ASSERT_EQ(client.try_call(request, reply, 2s), CallStatus::ok) << "call " << i;
    EXPECT_GE(Clock::now() - start, 50ms);
    EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
  }
  EXPECT_EQ(client.resent_requests(), 3u);
}

// ... and in poll(), which resends when due and never blocks.
TEST(Rpc, PollResendsALostRequest) {
  Participant server_side("server");
  Participant client_side("client");
  ForgetfulServer server(server_side);
  wbi::dds::ClientOptions options;
  options.resend_period = 20ms;
  Client client(client_side, kService, options);
  ASSERT_TRUE(client.wait_connected(10s));
  std::mt19937_64 rng(9);
  Request request;
  Reply reply;
  for (int i = 0; i < 3; ++i) {
    wbi::test::random_request(rng, 5, request);
    ASSERT_EQ(client.send(request, 2s), CallStatus::ok);
    CallStatus status = CallStatus::pending;
    ASSERT_TRUE(eventually([&] { return (status = client.poll(reply)) != CallStatus::pending; }));
    ASSERT_EQ(status, CallStatus::ok) << "call " << i;
    EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
  }
  EXPECT_EQ(client.resent_requests(), 3u);
}

// Connected means a server answered the client's probe, so it knows both of the
// client's endpoints: the first request, sent once and never again, is answered.
// Fresh clients (new endpoints; one participant, as a process has only 64
// participant ids that loopback discovery finds) meet matching half done.
TEST(Rpc, OnceConnectedTheFirstRequestIsAnsweredWithoutResending) {
  Participant server_side("server");
  Participant client_side("client");
  Server server(server_side, kService, wbi::test::toy_reply);
  wbi::dds::ClientOptions options;
  options.resend_period = 0ns;  // never resend requests
  for (int round = 0; round < 20; ++round) {
    Client client(client_side, kService, options);
    ASSERT_TRUE(client.wait_connected(10s)) << "round " << round;
    EXPECT_TRUE(client.connected());
    Request request;
    Reply reply;
    ASSERT_EQ(client.send(request, 5s), CallStatus::ok) << "round " << round;
    CallStatus status = CallStatus::pending;
    ASSERT_TRUE(eventually([&] { return (status = client.poll(reply)) != CallStatus::pending; }));
    EXPECT_EQ(status, CallStatus::ok) << "round " << round;
    EXPECT_EQ(client.resent_requests(), 0u);
  }
  EXPECT_GE(server.stats().probes, 20u);
}

// Copies of a request that is still being computed are dropped: a slow handler
// runs once however often the client resends.
TEST(Rpc, CopiesOfARequestInProgressAreComputedOnce) {
  Participant server_side("server");
  Participant client_side("client");
  Gate gate;
  std::atomic<int> computed{0};
  Server server(
      server_side, kService,
      [&](const Request& request, Reply& reply) {
        ++computed;
        gate.pass();
        wbi::test::toy_reply(request, reply);
      },
      worker_thread());
  wbi::dds::ClientOptions options;
  options.resend_period = 2ms;
  options.resend_period_max = 5ms;
  Client client(client_side, kService, options);
  ASSERT_TRUE(client.wait_connected(10s));
  Request request;
  auto call = std::async(std::launch::async, [&] {
    Reply reply;
    return client.try_call(request, reply, 10s);
  });
  ASSERT_TRUE(gate.wait_waiting(1));
  ASSERT_TRUE(eventually([&] { return server.stats().duplicates >= 3; }));
  EXPECT_EQ(computed.load(), 1);  // 3 copies came while it ran; none was computed
  gate.open();
  EXPECT_EQ(call.get(), CallStatus::ok);
  EXPECT_GE(client.resent_requests(), 3u);
}

TEST(Rpc, AsyncSendAndPollNeverBlock) {
  Participant server_side("server");
  Participant client_side("client");
  Client client(client_side, kService);
  Request request;
  Reply reply;
  EXPECT_EQ(client.poll(reply), CallStatus::idle);
  EXPECT_EQ(client.send(request, 1s), CallStatus::not_connected);  // no server yet
  Server server(server_side, kService, wbi::test::toy_reply);
  ASSERT_TRUE(client.wait_connected(10s));
  std::mt19937_64 rng(5);
  wbi::test::random_request(rng, 4, request);
  ASSERT_EQ(client.send(request, 5s), CallStatus::ok);
  EXPECT_EQ(client.send(request, 5s), CallStatus::busy);
  CallStatus status = CallStatus::pending;
  ASSERT_TRUE(eventually([&] { return (status = client.poll(reply)) != CallStatus::pending; }));
  EXPECT_EQ(status, CallStatus::ok);
  EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
  EXPECT_EQ(client.poll(reply), CallStatus::idle);
}

TEST(Rpc, ConcurrentClientsNeverGetEachOthersReplies) {
  Participant server_side("server");
  Server server(server_side, kService, wbi::test::toy_reply);
  constexpr int kClients = 4;
  constexpr int kCalls = 200;
  std::vector<std::future<std::string>> results;
  for (int c = 0; c < kClients; ++c) {
    results.push_back(std::async(std::launch::async, [c] {
      Participant side("client" + std::to_string(c));
      Client client(side, kService);
      std::mt19937_64 rng(100 + c);
      Request request;
      Reply reply;
      for (int i = 0; i < kCalls; ++i) {
        wbi::test::random_request(rng, 1 + (i + c) % 30, request);
        const CallStatus status = client.try_call(request, reply, 10s);
        if (status != CallStatus::ok) {
          return "client " + std::to_string(c) + " call " + std::to_string(i) + ": " +
                 wbi::dds::to_string(status);
        }
        const std::string mismatch = wbi::test::toy_mismatch(request, reply);
        if (!mismatch.empty()) {
          return "client " + std::to_string(c) + ": " + mismatch;
        }
      }
      return std::string();
    }));
  }
  for (auto& result : results) {
    EXPECT_EQ(result.get(), "");
  }
  // A call resends its request after 100 ms without a reply (client.hpp), so under
  // load the server may answer a request twice; every call got its own reply above.
  EXPECT_GE(server.stats().answered, static_cast<std::uint64_t>(kClients * kCalls));
}

}  // namespace
