// After warm-up, the request/reply layer adds no allocation per call: a call
// allocates only what Fast DDS 2.9's DataWriter::write allocates by itself
// for its two samples (measured with a plain Publisher::publish of the same
// sample: the writer builds std::function objects per sample), and nothing is
// allocated around a handler that reuses the reply's buffers. Counted with a
// replaced operator new, per thread.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <new>

#include <wbi/dds/client.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/server.hpp>
#include <wbi/dds/subscriber.hpp>

#include "rpc_fixture.hpp"

// GCC pairs the inlined std::free with the library's operator new and warns.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

namespace {
thread_local std::uint64_t allocations = 0;
}

void* operator new(std::size_t size) {
  ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) {
    return p;
  }
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

using namespace std::chrono_literals;
using Request = wbi::msg::ModelRequest;
using Reply = wbi::msg::ModelReply;

TEST(RpcAllocations, NonePerCallInTheCallingThreadAfterWarmUp) {
  wbi::dds::Participant server_side("server");
  wbi::dds::Participant client_side("client");
  std::atomic<std::uint64_t> handler_allocations{0};
  std::atomic<bool> counting{false};
  wbi::dds::Server<Request, Reply> server(server_side, "wbi/test/alloc",
                                          [&](const Request& request, Reply& reply) {
                                            const std::uint64_t before = allocations;
                                            wbi::test::toy_reply(request, reply);
                                            if (counting) {
                                              handler_allocations += allocations - before;
                                            }
                                          });
  wbi::dds::Client<Request, Reply> client(client_side, "wbi/test/alloc");
  std::mt19937_64 rng(1);
  Request request;
  Reply reply;
  wbi::test::random_request(rng, 20, request);
  for (int i = 0; i < 100; ++i) {  // warm-up: every buffer grows to size
    client.call(request, reply, 5s);
  }
  counting = true;
  const std::uint64_t before = allocations;
  for (int i = 0; i < 500; ++i) {
    ASSERT_EQ(client.try_call(request, reply, 5s), wbi::dds::CallStatus::ok);
  }
  const std::uint64_t in_calls = allocations - before;

  // The same sample through a plain publisher to one reader in another participant.
  wbi::dds::Publisher<Request> publisher(client_side, "wbi/test/alloc_raw",
                                         wbi::dds::qos::kRequestReply);
  wbi::dds::Subscriber<Request> subscriber(server_side, "wbi/test/alloc_raw",
                                           wbi::dds::qos::kRequestReply);
  ASSERT_TRUE(publisher.wait_for_subscribers(1, 10s));
  for (int i = 0; i < 100; ++i) {
    publisher.publish(request);
  }
  const std::uint64_t raw_before = allocations;
  for (int i = 0; i < 500; ++i) {
    publisher.publish(request);
  }
  const std::uint64_t in_writes = allocations - raw_before;
  std::cout << "allocations per call " << in_calls / 500.0 << ", per plain write "
            << in_writes / 500.0 << "\n";
  // Between participants of one process Fast DDS delivers in the writer's
  // thread: a call runs the request write, the server (handler and reply
  // write) and the reply hand-over all in the calling thread. So a call may
  // allocate what two plain writes do, and nothing more.
  EXPECT_LE(in_calls, 2 * in_writes)
      << "the request/reply layer allocates beyond Fast DDS's writes";
  EXPECT_EQ(handler_allocations.load(), 0u) << "allocations in the handler over 500 calls";
  EXPECT_EQ(wbi::test::toy_mismatch(request, reply), "");
}

}  // namespace
