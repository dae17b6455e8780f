#include "wbi/dds/rpc.hpp"

#include <sstream>

#include "wbi/dds/source_clock.hpp"

namespace wbi::dds {

const char* to_string(CallStatus status) {
  switch (status) {
    case CallStatus::ok:
      return "ok";
    case CallStatus::pending:
      return "pending";
    case CallStatus::idle:
      return "idle";
    case CallStatus::busy:
      return "busy";
    case CallStatus::not_connected:
      return "not connected";
    case CallStatus::no_reply:
      return "no reply";
    case CallStatus::send_failed:
      return "send failed";
  }
  return "unknown";
}

namespace {
std::string duration_text(std::chrono::nanoseconds timeout) {
  std::ostringstream text;
  const auto ns = timeout.count();
  if (ns % 1'000'000 == 0) {
    text << ns / 1'000'000 << " ms";
  } else {
    text << static_cast<double>(ns) * 1e-6 << " ms";
  }
  return text.str();
}
}  // namespace

std::string call_failure_message(const std::string& service, CallStatus status,
                                 std::chrono::nanoseconds timeout, std::uint64_t seq) {
  std::string text = "service '" + service + "': ";
  switch (status) {
    case CallStatus::not_connected:
      return text + "timed out after " + duration_text(timeout) +
             " waiting for a server (no server matched both the request and the reply topic)";
    case CallStatus::no_reply:
      return text + "timed out: no reply to request " + std::to_string(seq) + " within " +
             duration_text(timeout);
    case CallStatus::send_failed:
      return text + "DDS refused request " + std::to_string(seq);
    case CallStatus::busy:
      return text + "a call is already in flight on this client";
    default:
      return text + to_string(status);
  }
}

namespace detail {
std::int64_t system_now_ns() { return source_clock_now_ns(); }
}  // namespace detail

}  // namespace wbi::dds
