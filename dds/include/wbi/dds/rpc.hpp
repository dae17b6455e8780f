// What Client<Req, Rep> and Server<Req, Rep> share: the request/reply message
// contract, call outcomes and their errors.
//
// A service named S uses two topics, S/request and S/reply (QoS profile
// wbi.request_reply: best effort, so delivery is the client's job: it sends a
// request again while no reply came, like an RPC over UDP). Correlation: every
// request carries the client's id and a per-client sequence number, and its
// reply carries both back. The client id is the GUID of the client's reply
// reader (32 hex digits), so the server can tell whether that reader has
// matched its reply writer before answering: a reply written earlier could be
// lost (the classic lost-first-reply of request/reply over DDS). Sequence
// number 0 is a connection probe (kProbeSeq), answered by the server itself.
// See client.hpp and server.hpp.
#pragma once

#include <algorithm>
#include <chrono>
#include <concepts>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "message_traits.hpp"

namespace wbi::dds {

// A request type and its reply type: both carry `client_id` (a string) and `seq`.
template <class Req, class Rep>
concept RequestReply = Message<Req> && Message<Rep> && requires(Req& request, Rep& reply) {
  { request.client_id().c_str() } -> std::convertible_to<const char*>;
  { request.seq() } -> std::convertible_to<std::uint64_t>;
  { reply.client_id().c_str() } -> std::convertible_to<const char*>;
  { reply.seq() } -> std::convertible_to<std::uint64_t>;
};

// A request that carries the caller's deadline (system clock, ns since the Unix
// epoch, 0 for none): the server drops it when it cannot start it in time.
template <class Req>
concept HasDeadline = requires(Req& request) {
  request.deadline_ns() = std::int64_t{0};
};

// A reply with an error text: the server puts a handler's exception there.
template <class Rep>
concept HasErrorText = requires(Rep& reply) {
  reply.error() = "text";
};

namespace topics {
inline std::string service_request(const std::string& service) { return service + "/request"; }
inline std::string service_reply(const std::string& service) { return service + "/reply"; }
}  // namespace topics

enum class CallStatus {
  ok,             // the reply is in the caller's reply object
  pending,        // poll(): no reply yet, deadline not reached
  idle,           // poll(): no call in flight
  busy,           // send(): a call is already in flight on this client
  not_connected,  // deadline reached before a server matched both topics; nothing sent
  no_reply,       // deadline reached after sending, without the reply
  send_failed,    // DDS refused the request sample
};

const char* to_string(CallStatus status);

// Why a call failed, in one line naming the service, e.g.
// "service 'wbi/icub/model': no reply to request 17 within 200 ms".
std::string call_failure_message(const std::string& service, CallStatus status,
                                 std::chrono::nanoseconds timeout, std::uint64_t seq);

// A failed call. what() names the service and the reason.
class CallError : public std::runtime_error {
 public:
  CallError(std::string service, CallStatus status, std::chrono::nanoseconds timeout,
            std::uint64_t seq)
      : std::runtime_error(call_failure_message(service, status, timeout, seq)),
        service_(std::move(service)),
        status_(status) {}
  const std::string& service() const { return service_; }
  CallStatus status() const { return status_; }

 private:
  std::string service_;
  CallStatus status_;
};

// The deadline ran out (not_connected or no_reply).
class TimeoutError : public CallError {
 public:
  using CallError::CallError;
};

// The sequence number of a connection probe: a client sends it until a server
// answers (see Client::wait_connected); a server answers it without its handler.
inline constexpr std::uint64_t kProbeSeq = 0;

namespace detail {
// System clock now [ns since the Unix epoch]: the time base of request deadlines.
std::int64_t system_now_ns();

// When to send a request again for want of a reply: `first` after it was sent,
// then twice as long after each resend, at most `max` (a busy server is not
// flooded). first == 0: never.
class ResendSchedule {
 public:
  using Clock = std::chrono::steady_clock;
  ResendSchedule(std::chrono::nanoseconds first, std::chrono::nanoseconds max)
      : first_(first), max_(std::max(first, max)) {}
  // A first send: the schedule starts afresh.
  void sent(Clock::time_point now) {
    started_ = true;
    interval_ = first_;
    next_ = now + first_;
  }
  // A send again: the next interval doubles.
  void resent(Clock::time_point now) {
    interval_ = std::min(2 * interval_, max_);
    next_ = now + interval_;
  }
  // sent() for the first send since the start or reset(), resent() after it.
  void record(Clock::time_point now) { started_ ? resent(now) : sent(now); }
  bool started() const { return started_; }
  void reset() { started_ = false; }
  bool due(Clock::time_point now) const { return first_.count() > 0 && now >= next_; }
  // The next resend time (time_point::max() when never).
  Clock::time_point next() const { return first_.count() > 0 ? next_ : Clock::time_point::max(); }

 private:
  std::chrono::nanoseconds first_;
  std::chrono::nanoseconds max_;
  bool started_ = false;
  std::chrono::nanoseconds interval_{};
  Clock::time_point next_{};
};
}  // namespace detail

}  // namespace wbi::dds
