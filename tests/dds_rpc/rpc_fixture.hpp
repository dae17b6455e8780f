// A toy service for the request/reply tests: the reply to a ModelRequest is a
// pure function of the request, so a client can check every reply it gets.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>

#include <wbi/msg/model.h>

namespace wbi::test {

// results[0] = q² + 3 dq (element-wise); results[1] = (seq, robot name length).
inline void toy_reply(const wbi::msg::ModelRequest& request, wbi::msg::ModelReply& reply) {
  const auto& q = request.state().q();
  const auto& dq = request.state().dq();
  reply.error() = "";
  reply.compute_ns(0);
  reply.results().resize(2);
  auto& first = reply.results()[0];
  first.operation(wbi::msg::GRAVITY_FORCES);
  first.rows(static_cast<std::uint32_t>(q.size()));
  first.cols(1);
  first.data().resize(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) {
    first.data()[i] = q[i] * q[i] + 3.0 * (i < dq.size() ? dq[i] : 0.0);
  }
  auto& second = reply.results()[1];
  second.operation(wbi::msg::COM);
  second.rows(2);
  second.cols(1);
  second.data().resize(2);
  second.data()[0] = static_cast<double>(request.seq());
  second.data()[1] = static_cast<double>(request.robot().size());
}

// A random state of n joints.
inline void random_request(std::mt19937_64& rng, std::size_t n, wbi::msg::ModelRequest& request) {
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  request.robot("toy");
  request.state().q().resize(n);
  request.state().dq().resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    request.state().q()[i] = value(rng);
    request.state().dq()[i] = value(rng);
  }
}

// Empty when reply is the toy reply to request, else what differs.
inline std::string toy_mismatch(const wbi::msg::ModelRequest& request,
                                const wbi::msg::ModelReply& reply) {
  wbi::msg::ModelReply expected;
  toy_reply(request, expected);
  std::ostringstream why;
  if (reply.seq() != request.seq()) {
    why << "seq " << reply.seq() << " != " << request.seq();
  } else if (reply.client_id() != request.client_id()) {
    why << "client id " << reply.client_id().c_str() << " != " << request.client_id().c_str();
  } else if (reply.error().size() != 0) {
    why << "error: " << reply.error().c_str();
  } else if (reply.results().size() != 2 ||
             reply.results()[0].data() != expected.results()[0].data() ||
             reply.results()[1].data() != expected.results()[1].data()) {
    why << "results differ for seq " << request.seq();
  }
  return why.str();
}

}  // namespace wbi::test
