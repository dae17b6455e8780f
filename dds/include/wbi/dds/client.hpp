// Client<Req, Rep>: calls a service (see rpc.hpp) with a deadline.
//
//   wbi::dds::Client<ModelRequest, ModelReply> client(participant, "wbi/icub/model");
//   client.call(request, reply, 200ms);   // throws TimeoutError naming the service
//
// Connected means both of the client's endpoints are matched (its request
// writer with a server's request reader, its reply reader with a server's
// reply writer) and a server answered the client's connection probe: then the
// server has matched both of them too, and a request sent now is answered.
// Discovery is not symmetric in time, so without the probe the first request
// after matching could reach a server that does not know the client yet.
// A call first waits (within its deadline) to be connected, so a client may
// start before its server. Replies of other clients and stale replies (of
// calls that timed out) are dropped by id and sequence number.
//
// Delivery: the wbi.request_reply profile is best effort (a reliable round
// trip costs about twice as much here, dds/README.md "Latency"); a request
// without a reply is sent again (same id and sequence number) on the schedule
// of ClientOptions, by call()/try_call() while they wait and by poll() when it
// finds the resend due. So handlers must be idempotent: a copy that reaches
// the server after its reply was written is answered again.
//
// One call in flight per client: calls from several threads are serialised;
// give each thread its own client for concurrency. The blocking call() suits
// tools and setup code; a periodic update() uses send() + poll(), which never
// block. After warm-up (request and reply sequences grown to size) a call
// allocates only inside Fast DDS for unbounded members.
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
  // A request without a reply is sent again after resend_period, then after
  // twice as long each time, at most resend_period_max, until its deadline
  // (over a reliable profile too: a KEEP_LAST history that overflows drops
  // samples for good). The first resend comes well after a normal round trip
  // (~30-100 us here) and soon enough to save a 1 kHz loop's next tick; a link
  // whose round trip is longer (other hosts, emulated delay) wants a longer one,
  // else most calls are sent twice. 0: never resend (probes are still resent).
  std::chrono::nanoseconds resend_period = std::chrono::milliseconds(2);
  std::chrono::nanoseconds resend_period_max = std::chrono::milliseconds(100);
  // ProducerPolicy::one(): take the replies of the first server heard only (a
  // second server of the same service is dropped, see producers.hpp).
  ProducerPolicy producers;
  // The replies come on a receive thread of their own: a call may then block
  // on the thread that delivers the participant's other samples (a
  // controller's cycle in its state's callback), which would else never
  // deliver the reply. One thread (per transport) more for each such client.
  bool reply_thread_of_its_own = false;
};

template <class Req, class Rep>
requires RequestReply<Req, Rep>
class Client : private detail::ReaderSink {
 public:
  // service: the service name, e.g. topics::model_service("icub").
  Client(Participant& participant, std::string service, const ClientOptions& options = {})
      : service_(std::move(service)),
        resend_(options.resend_period, options.resend_period_max),
        send_probes_(kProbeFirst, kProbeMax),
        request_writer_(participant, topics::service_request(service_),
                        new typename MessageTraits<Req>::TypeSupport(), options.qos_profile),
        reply_reader_(participant, topics::service_reply(service_),
                      new typename MessageTraits<Rep>::TypeSupport(), options.qos_profile, *this,
                      {.own_receive_thread = options.reply_thread_of_its_own}, options.producers) {
    std::lock_guard lock(mutex_);
    const std::string id = detail::guid_hex(reply_reader_.guid());
    std::memcpy(client_id_, id.c_str(), id.size() + 1);
    probe_.client_id() = client_id_;
    probe_.seq() = kProbeSeq;
  }

  ~Client() override = default;
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  const std::string& service() const { return service_; }
  // The id this client puts in its requests (its reply reader's GUID, 32 hex digits).
  const char* client_id() const { return client_id_; }

  // Both endpoints matched and a server answered the connection probe (see above).
  bool connected() const {
    std::lock_guard lock(mutex_);
    return matched() && confirmed_;
  }
  // Waits until connected, sending connection probes once both endpoints are matched.
  bool wait_connected(std::chrono::nanoseconds timeout) {
    return wait_connected_until(std::chrono::steady_clock::now() + timeout);
  }

  // Sends request (its client_id, seq and, if it has one, deadline_ns are set
  // here) and waits for the reply, at most `timeout` in all (waiting to be
  // connected included), sending it again while no reply comes (ClientOptions).
  // Returns ok with the reply in `reply`, or why not (busy while a send() is in
  // flight and not yet polled or expired).
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
    while (!replied_.wait_until(lock, std::min(deadline, resend_.next()), [&] { return ready_; })) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= deadline) {
        give_up();
        return CallStatus::no_reply;
      }
      lock.unlock();
      request_writer_.write(&request);  // same id and seq: whichever reply comes first is taken
      lock.lock();
      ++resent_;
      resend_.resent(now);
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
  // not_connected: a connection probe went out (when due); try again later.
  // The request is copied for poll()'s resends.
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
      probe_if_due();
      return CallStatus::not_connected;
    }
    send_probes_.reset();  // should the connection be lost, the first probe goes out at once
    const CallStatus sent = start(request, std::chrono::steady_clock::now() + timeout);
    if (sent == CallStatus::ok) {
      in_flight_ = request;  // after the write: no delay; buffers reused after warm-up
    }
    return sent;
  }

  // The outcome of the call started by send(): ok (reply taken), pending, no_reply
  // (its deadline passed; the call is abandoned) or idle (no call in flight).
  // Sends the request again when the resend is due (a write, never a wait).
  CallStatus poll(Rep& reply) {
    const auto now = std::chrono::steady_clock::now();
    {
      std::lock_guard lock(mutex_);
      if (ready_) {
        take(reply);
        return CallStatus::ok;
      }
      if (awaited_ == 0) {
        return CallStatus::idle;
      }
      if (now >= call_deadline_) {
        give_up();
        return CallStatus::no_reply;
      }
    }
    std::unique_lock call_lock(call_mutex_, std::try_to_lock);  // guards in_flight_ and resend_
    if (call_lock.owns_lock() && resend_.due(now)) {
      request_writer_.write(&in_flight_);
      resend_.resent(now);
      std::lock_guard lock(mutex_);
      ++resent_;
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
  // Probes go out every kProbeFirst at first: a server that has not matched the
  // client's request writer yet drops them, and matching takes a few ms.
  static constexpr std::chrono::nanoseconds kProbeFirst = std::chrono::milliseconds(1);
  static constexpr std::chrono::nanoseconds kProbeMax = std::chrono::milliseconds(50);

  bool matched() const { return request_writer_.matched() > 0 && reply_reader_.matched() > 0; }

 public:
  // With ClientOptions::producers one: the server taken and what was dropped.
  ProducerCounts producers() const { return reply_reader_.producers(); }

 private:
  bool wait_connected_until(std::chrono::steady_clock::time_point deadline) {
    const auto left = [&] { return deadline - std::chrono::steady_clock::now(); };
    {
      std::lock_guard lock(mutex_);
      if (!matched()) {
        confirmed_ = false;  // the servers that answered are gone
      }
    }
    if (!request_writer_.wait_matched(1, left()) || !reply_reader_.wait_matched(1, left())) {
      return false;
    }
    detail::ResendSchedule probes(kProbeFirst, kProbeMax);
    std::unique_lock lock(mutex_);
    while (!confirmed_) {
      const auto now = std::chrono::steady_clock::now();
      if (now >= deadline) {
        return false;
      }
      if (!probes.started() || probes.due(now)) {
        lock.unlock();
        request_writer_.write(&probe_);
        lock.lock();
        probes.record(now);
      }
      replied_.wait_until(lock, std::min(deadline, probes.next()), [&] { return confirmed_; });
    }
    return true;
  }

  // send() when matched but not confirmed: a probe now and then. Caller holds call_mutex_.
  void probe_if_due() {
    if (!matched()) {
      return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (!send_probes_.started() || send_probes_.due(now)) {
      request_writer_.write(&probe_);
      send_probes_.record(now);
    }
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
    const auto now = std::chrono::steady_clock::now();
    if (!request_writer_.write(&request)) {
      std::lock_guard lock(mutex_);
      awaited_ = 0;
      return CallStatus::send_failed;
    }
    resend_.sent(now);
    return CallStatus::ok;
  }

  // No reply within the deadline: a late reply is dropped, and the next call
  // probes again (the server may be gone). Caller holds mutex_.
  void give_up() {
    awaited_ = 0;
    confirmed_ = false;
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
      if (std::strncmp(incoming_.client_id().c_str(), client_id_, sizeof(client_id_)) != 0) {
        ++dropped_;  // another client's
        return;
      }
      if (incoming_.seq() == kProbeSeq) {
        confirmed_ = true;
      } else if (awaited_ == 0 || incoming_.seq() != awaited_) {
        ++dropped_;  // late, or a second reply to a resent request
        return;
      } else {
        using std::swap;
        swap(slot_, incoming_);
        awaited_ = 0;
        ready_ = true;
        confirmed_ = true;
      }
    }
    replied_.notify_all();  // a call and wait_connected() may both wait
  }

  std::string service_;
  std::mutex call_mutex_;  // one call in flight; guards what follows up to mutex_
  std::uint64_t next_seq_ = 0;
  std::uint64_t last_seq_ = 0;
  detail::ResendSchedule resend_;       // of the call in flight
  detail::ResendSchedule send_probes_;  // of send()'s probes, started by the first since connected
  Req in_flight_;                       // send()'s request, for poll()'s resends
  Req probe_;                           // client_id and kProbeSeq, else default

  mutable std::mutex mutex_;  // guards what follows, shared with the DDS thread
  std::condition_variable replied_;
  char client_id_[33] = {};
  std::uint64_t awaited_ = 0;  // seq of the call in flight, 0 when none
  bool ready_ = false;         // slot_ holds its reply
  bool confirmed_ = false;     // a server answered a probe or a request (see connected())
  std::chrono::steady_clock::time_point call_deadline_{};
  std::uint64_t dropped_ = 0;
  std::uint64_t resent_ = 0;
  Rep slot_;
  Rep incoming_;  // written only on the DDS thread that takes samples

  detail::Writer request_writer_;
  detail::Reader reply_reader_;  // last: destroyed first, so no callback outlives the members above
};

}  // namespace wbi::dds
