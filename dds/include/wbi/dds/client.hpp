// Client<Req, Rep>: calls a service (see rpc.hpp) with a deadline.
//
//   wbi::dds::Client<ModelRequest, ModelReply> client(participant, "wbi/icub/model");
//   client.call(request, reply, 200ms);   // throws TimeoutError naming the service
//
// Connected means both of the client's endpoints are matched: its request
// writer with a server's request reader and its reply reader with a server's
// reply writer. A call first waits (within its deadline) to be connected, so a
// client may start before its server. Replies of other clients and stale
// replies (of calls that timed out) are dropped by id and sequence number.
//
// One call in flight per client: calls from several threads are serialised;
// give each thread its own client for concurrency. The blocking call() suits
// tools and setup code; a periodic update() uses send() + poll(), which never
// block (and never resend: a lost sample makes that call time out). A blocking
// call resends its request while no reply comes (ClientOptions::resend_period).
// After warm-up (reply sequences grown to size) a call allocates only
// inside Fast DDS for unbounded members.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>
#include <utility>

#include "detail/endpoints.hpp"
#include "participant.hpp"
#include "rpc.hpp"

namespace wbi::dds {

struct ClientOptions {
  std::string qos_profile = qos::kRequestReply;
  // call()/try_call() send the request again (same id and sequence number)
  // when no reply came within this period, until the deadline: a reliable
  // KEEP_LAST history drops unacknowledged samples when it overflows (many
  // clients, a busy reader), so a sample can be lost for good. Handlers must
  // be idempotent (a duplicate is answered again; the client keeps the first
  // reply). 0: never resend.
  std::chrono::nanoseconds resend_period = std::chrono::milliseconds(100);
};

template <class Req, class Rep>
requires RequestReply<Req, Rep>
class Client : private detail::ReaderSink {
 public:
  // service: the service name, e.g. topics::model_service("icub").
  Client(Participant& participant, std::string service, const ClientOptions& options = {})
      : service_(std::move(service)),
        resend_period_(options.resend_period),
        request_writer_(participant, topics::service_request(service_),
                        new typename MessageTraits<Req>::TypeSupport(), options.qos_profile),
        reply_reader_(participant, topics::service_reply(service_),
                      new typename MessageTraits<Rep>::TypeSupport(), options.qos_profile, *this) {
    std::lock_guard lock(mutex_);
    const std::string id = detail::guid_hex(reply_reader_.guid());
    std::memcpy(client_id_, id.c_str(), id.size() + 1);
  }

  ~Client() override = default;
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  const std::string& service() const { return service_; }
  // The id this client puts in its requests (its reply reader's GUID, 32 hex digits).
  const char* client_id() const { return client_id_; }

  bool connected() const { return request_writer_.matched() > 0 && reply_reader_.matched() > 0; }
  bool wait_connected(std::chrono::nanoseconds timeout) const {
    return wait_connected_until(std::chrono::steady_clock::now() + timeout);
  }

  // Sends request (its client_id, seq and, if it has one, deadline_ns are set
  // here) and waits for the reply, at most `timeout` in all (waiting to be
  // connected included). Returns ok with the reply in `reply`, or why not
  // (busy while a send() is in flight and not yet polled or expired).
  CallStatus try_call(Req& request, Rep& reply, std::chrono::nanoseconds timeout) {
    std::lock_guard call_lock(call_mutex_);
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    {
      std::lock_guard lock(mutex_);
      if (ready_ || (awaited_ != 0 && std::chrono::steady_clock::now() < call_deadline_)) {
        return CallStatus::busy;  // a send() is in flight: poll() it first
      }
    }
    if (!wait_connected_until(deadline)) {
      return CallStatus::not_connected;
    }
    const CallStatus sent = start(request, deadline);
    if (sent != CallStatus::ok) {
      return sent;
    }
    std::unique_lock lock(mutex_);
    auto resend_at =
        resend_period_.count() > 0 ? std::chrono::steady_clock::now() + resend_period_ : deadline;
    while (!replied_.wait_until(lock, std::min(deadline, resend_at), [&] { return ready_; })) {
      if (std::chrono::steady_clock::now() >= deadline) {
        awaited_ = 0;  // a late reply is dropped
        return CallStatus::no_reply;
      }
      lock.unlock();
      request_writer_.write(&request);  // same id and seq: whichever reply comes first is taken
      lock.lock();
      ++resent_;
      resend_at += resend_period_;
    }
    take(reply);
    return CallStatus::ok;
  }

  // try_call that throws TimeoutError (or CallError when the sample was refused),
  // whose message names the service.
  void call(Req& request, Rep& reply, std::chrono::nanoseconds timeout) {
    const CallStatus status = try_call(request, reply, timeout);
    if (status == CallStatus::ok) {
      return;
    }
    if (status == CallStatus::not_connected || status == CallStatus::no_reply) {
      throw TimeoutError(service_, status, timeout, last_seq_);
    }
    throw CallError(service_, status, timeout, last_seq_);
  }

  // Non-blocking call, for periodic loops: sends request if connected and no
  // call is in flight (busy otherwise); poll() then hands over the reply.
  CallStatus send(Req& request, std::chrono::nanoseconds timeout) {
    std::unique_lock call_lock(call_mutex_, std::try_to_lock);
    if (!call_lock.owns_lock()) {
      return CallStatus::busy;
    }
    {
      std::lock_guard lock(mutex_);
      if (awaited_ != 0 || ready_) {
        return CallStatus::busy;
      }
    }
    if (!connected()) {
      return CallStatus::not_connected;
    }
    return start(request, std::chrono::steady_clock::now() + timeout);
  }

  // The outcome of the call started by send(): ok (reply taken), pending, no_reply
  // (its deadline passed; the call is abandoned) or idle (no call in flight).
  CallStatus poll(Rep& reply) {
    std::lock_guard lock(mutex_);
    if (ready_) {
      take(reply);
      return CallStatus::ok;
    }
    if (awaited_ == 0) {
      return CallStatus::idle;
    }
    if (std::chrono::steady_clock::now() >= call_deadline_) {
      awaited_ = 0;
      return CallStatus::no_reply;
    }
    return CallStatus::pending;
  }

  // Sequence number of the last request sent (0 before the first).
  std::uint64_t last_seq() const { return last_seq_; }
  // Replies dropped because they were another client's, or late.
  std::uint64_t dropped_replies() const {
    std::lock_guard lock(mutex_);
    return dropped_;
  }
  // Requests sent again for want of a reply (see ClientOptions::resend_period).
  std::uint64_t resent_requests() const {
    std::lock_guard lock(mutex_);
    return resent_;
  }

 private:
  bool wait_connected_until(std::chrono::steady_clock::time_point deadline) const {
    const auto left = [&] { return deadline - std::chrono::steady_clock::now(); };
    return request_writer_.wait_matched(1, left()) && reply_reader_.wait_matched(1, left());
  }

  CallStatus start(Req& request, std::chrono::steady_clock::time_point deadline) {
    const std::uint64_t seq = ++next_seq_;
    last_seq_ = seq;
    request.client_id() = client_id_;
    request.seq() = seq;
    if constexpr (HasDeadline<Req>) {
      request.deadline_ns() =
          detail::system_now_ns() + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                        deadline - std::chrono::steady_clock::now())
                                        .count();
    }
    {
      std::lock_guard lock(mutex_);
      awaited_ = seq;
      ready_ = false;
      call_deadline_ = deadline;
    }
    if (!request_writer_.write(&request)) {
      std::lock_guard lock(mutex_);
      awaited_ = 0;
      return CallStatus::send_failed;
    }
    return CallStatus::ok;
  }

  // Caller holds mutex_ and ready_ is true.
  void take(Rep& reply) {
    using std::swap;
    swap(reply, slot_);  // buffers circulate: no allocation once all have grown
    ready_ = false;
  }

  void* storage() override { return &incoming_; }

  void on_sample(const detail::SampleInfo& /*info*/) override {
    {
      std::lock_guard lock(mutex_);
      if (awaited_ == 0 || incoming_.seq() != awaited_ ||
          std::strncmp(incoming_.client_id().c_str(), client_id_, sizeof(client_id_)) != 0) {
        ++dropped_;
        return;
      }
      using std::swap;
      swap(slot_, incoming_);
      awaited_ = 0;
      ready_ = true;
    }
    replied_.notify_one();
  }

  std::string service_;
  std::chrono::nanoseconds resend_period_;
  std::mutex call_mutex_;  // one call in flight
  std::uint64_t next_seq_ = 0;
  std::uint64_t last_seq_ = 0;

  mutable std::mutex mutex_;  // guards what follows, shared with the DDS thread
  std::condition_variable replied_;
  char client_id_[33] = {};
  std::uint64_t awaited_ = 0;  // seq of the call in flight, 0 when none
  bool ready_ = false;         // slot_ holds its reply
  std::chrono::steady_clock::time_point call_deadline_{};
  std::uint64_t dropped_ = 0;
  std::uint64_t resent_ = 0;
  Rep slot_;
  Rep incoming_;  // written only on the DDS thread that takes samples

  detail::Writer request_writer_;
  detail::Reader reply_reader_;  // last: destroyed first, so no callback outlives the members above
};

}  // namespace wbi::dds
