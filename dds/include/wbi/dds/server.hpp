// Server<Req, Rep>: answers the requests of a service (see rpc.hpp) with a
// handler, for any number of clients.
//
//   wbi::dds::Server<ModelRequest, ModelReply> server(participant, "wbi/icub/model",
//       [&](const ModelRequest& request, ModelReply& reply) { ... });
//
// Request lifecycle
//   taken      on the DDS thread of the request reader, copied into a free slot
//              of a fixed pool (no allocation after warm-up);
//   held       when the client's reply reader has not matched the reply writer
//              yet: a reply written now could be lost. Released as soon as it
//              matches; dropped after `match_wait` or at the request's deadline;
//   queued     then handled in arrival order, straight on the DDS thread when
//              nothing else is queued, else by the server's worker thread
//              (see ServerOptions::handle_on_dds_thread);
//   dropped    when its client is gone (its reply reader unmatched), when its
//              deadline passed before it could start, when it is a copy of a
//              request still held, queued or running (clients resend, see
//              client.hpp), or when the pool is full (the client then gets an
//              error reply if Rep has an error text).
// A copy that arrives after the reply was written is answered again (the
// reply may have been lost): handlers must be idempotent. A connection probe
// (seq kProbeSeq) is answered at once on the DDS thread, without the handler,
// when its client's reply reader has matched, and dropped otherwise (the client
// probes again): an answered probe tells the client both paths work.
// The handler fills every field of the reply except client_id and seq, which the
// server copies from the request. Handlers run one at a time. An exception from
// the handler becomes the reply's error text (when Rep has one), never silence.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "detail/endpoints.hpp"
#include "participant.hpp"
#include "rpc.hpp"

namespace wbi::dds {

struct ServerOptions {
  std::string qos_profile = qos::kRequestReply;
  // Longest a request waits for its client's reply reader to match.
  std::chrono::nanoseconds match_wait = std::chrono::seconds(2);
  // Requests held or queued at once.
  std::size_t capacity = 64;
  // true: a request whose client is matched is handled directly on the DDS
  // thread that received it when nothing is queued: no thread hand-off, about
  // 40 us less per call here; that thread is then busy for one request at most.
  // false: always on the worker thread (for handlers that may take long).
  bool handle_on_dds_thread = true;
};

struct ServerStats {
  std::uint64_t received = 0;
  std::uint64_t answered = 0;
  std::uint64_t held = 0;               // had to wait for their client's reply reader
  std::uint64_t dropped_gone = 0;       // client gone before the reply
  std::uint64_t dropped_expired = 0;    // deadline passed before the request could start
  std::uint64_t dropped_unmatched = 0;  // client's reply reader never matched within match_wait
  std::uint64_t rejected_full = 0;      // pool full
  std::uint64_t handler_errors = 0;     // handler threw
  std::uint64_t duplicates = 0;         // copies of a request still held, queued or running
  std::uint64_t answered_again = 0;     // replies to a request answered before (a resent copy)
  std::uint64_t probes = 0;             // connection probes answered
};

template <class Req, class Rep>
requires RequestReply<Req, Rep>
class Server : private detail::ReaderSink, private detail::MatchObserver {
 public:
  // Called with a request; fills reply. Runs on the worker (or DDS) thread.
  using Handler = std::function<void(const Req& request, Rep& reply)>;

  Server(Participant& participant, std::string service, Handler handler,
         const ServerOptions& options = {})
      : service_(std::move(service)),
        handler_(std::move(handler)),
        options_(options),
        slots_(options.capacity),
        meta_(options.capacity),
        free_(free_list(options.capacity)),
        ring_(options.capacity),
        reply_writer_(participant, topics::service_reply(service_),
                      new typename MessageTraits<Rep>::TypeSupport(), options.qos_profile, this),
        request_reader_(participant, topics::service_request(service_),
                        new typename MessageTraits<Req>::TypeSupport(), options.qos_profile,
                        *this) {
    worker_ = std::thread([this] { work(); });
  }

  ~Server() override {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    worker_.join();
  }
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  const std::string& service() const { return service_; }
  // Client reply readers currently matched.
  int clients() const {
    std::lock_guard lock(mutex_);
    return static_cast<int>(matched_.size());
  }
  // Waits until at least `count` clients' reply readers are matched.
  bool wait_for_clients(int count, std::chrono::nanoseconds timeout) const {
    return reply_writer_.wait_matched(count, timeout);
  }
  ServerStats stats() const {
    std::lock_guard lock(mutex_);
    ServerStats copy = stats_;
    copy.answered = answered_.load();
    copy.handler_errors = handler_errors_.load();
    copy.answered_again = answered_again_.load();
    return copy;
  }

 private:
  enum class SlotState { free, held, queued, cancelled, running };
  struct Slot {
    SlotState state = SlotState::free;
    bool has_guid = false;
    detail::Guid guid{};
    std::uint64_t seq = 0;
    std::int64_t hold_until_ns = 0;  // steady clock, while held
    std::int64_t deadline_ns = 0;    // system clock, 0: none
  };

  // ---- DDS thread of the request reader ----
  void* storage() override { return &incoming_; }

  void on_sample(const detail::SampleInfo& info) override {
    Slot slot;
    slot.has_guid = detail::parse_guid_hex(incoming_.client_id().c_str(), slot.guid);
    slot.seq = incoming_.seq();
    if constexpr (HasDeadline<Req>) {
      slot.deadline_ns = incoming_.deadline_ns();
    }
    std::unique_lock lock(mutex_);
    if (slot.has_guid && is_gone(slot.guid)) {
      if (slot.seq != kProbeSeq) {
        ++stats_.dropped_gone;
      }
      return;
    }
    const bool matched = !slot.has_guid || is_matched(slot.guid);
    if (slot.seq == kProbeSeq) {
      if (matched) {
        ++stats_.probes;
        lock.unlock();
        answer_aside(incoming_, nullptr);
      }
      return;
    }
    ++stats_.received;
    if (expired(slot.deadline_ns)) {
      ++stats_.dropped_expired;
      return;
    }
    if (slot.has_guid && in_progress(slot)) {
      ++stats_.duplicates;
      return;
    }
    if (options_.handle_on_dds_thread && matched && queued_ == 0 && !running_) {
      running_ = true;
      running_slot_ = slot;
      lock.unlock();
      handle(incoming_, slot);
      lock.lock();
      running_ = false;
      if (queued_ > 0) {
        wake_.notify_one();
      }
      return;
    }
    if (free_.empty()) {
      ++stats_.rejected_full;
      lock.unlock();
      if constexpr (HasErrorText<Rep>) {
        answer_aside(incoming_, "server busy: too many requests queued");
      }
      return;
    }
    const int index = free_.back();
    free_.pop_back();
    using std::swap;
    swap(slots_[index], incoming_);
    meta_[index] = slot;
    if (matched) {
      enqueue(index);
    } else {
      meta_[index].state = SlotState::held;
      meta_[index].hold_until_ns = info.received_ns + options_.match_wait.count();
      ++stats_.held;
      ++held_changes_;  // the worker recomputes its wake-up time
    }
    lock.unlock();
    wake_.notify_one();
  }

  // ---- DDS thread of discovery: a client's reply reader came or went ----
  void on_match_changed(const detail::Guid& reader, bool now_matched) override {
    {
      std::lock_guard lock(mutex_);
      if (now_matched) {
        if (!is_matched(reader)) {
          matched_.push_back(reader);
        }
      } else {
        std::erase(matched_, reader);
        gone_[gone_next_] = reader;
        gone_next_ = (gone_next_ + 1) % gone_.size();
        gone_count_ = std::min(gone_count_ + 1, gone_.size());
      }
      for (std::size_t i = 0; i < meta_.size(); ++i) {
        Slot& slot = meta_[i];
        if (!slot.has_guid || slot.guid != reader) {
          continue;
        }
        if (now_matched && slot.state == SlotState::held) {
          enqueue(static_cast<int>(i));
        } else if (!now_matched && slot.state == SlotState::held) {
          ++stats_.dropped_gone;
          release(static_cast<int>(i));
        } else if (!now_matched && slot.state == SlotState::queued) {
          slot.state = SlotState::cancelled;  // freed by the worker when dequeued
        }
      }
    }
    wake_.notify_one();
  }

  // ---- worker thread ----
  void work() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      if (queued_ > 0 && !running_) {
        const int index = dequeue();
        Slot& slot = meta_[index];
        if (slot.state == SlotState::cancelled) {
          ++stats_.dropped_gone;
          release(index);
          continue;
        }
        if (expired(slot.deadline_ns)) {
          ++stats_.dropped_expired;
          release(index);
          continue;
        }
        slot.state = SlotState::running;
        running_ = true;
        running_slot_ = slot;
        lock.unlock();
        handle(slots_[index], running_slot_);
        lock.lock();
        running_ = false;
        release(index);
        continue;
      }
      // Drop held requests whose wait is over; sleep until the next one's end.
      const std::int64_t now = detail::steady_now_ns();
      std::int64_t next = INT64_MAX;
      for (std::size_t i = 0; i < meta_.size(); ++i) {
        Slot& slot = meta_[i];
        if (slot.state != SlotState::held) {
          continue;
        }
        if (slot.hold_until_ns <= now || expired(slot.deadline_ns)) {
          ++(expired(slot.deadline_ns) ? stats_.dropped_expired : stats_.dropped_unmatched);
          release(static_cast<int>(i));
        } else {
          next = std::min(next, slot.hold_until_ns);
        }
      }
      const std::uint64_t seen = held_changes_;
      const auto woken = [&] {
        return stop_ || (queued_ > 0 && !running_) || held_changes_ != seen;
      };
      if (next == INT64_MAX) {
        wake_.wait(lock, woken);
      } else {
        wake_.wait_for(lock, std::chrono::nanoseconds(next - now), woken);
      }
    }
  }

  // Runs the handler and writes the reply; one at a time (running_).
  void handle(const Req& request, const Slot& slot) {
    try {
      handler_(request, reply_);
    } catch (const std::exception& error) {
      handler_errors_.fetch_add(1);
      if constexpr (HasErrorText<Rep>) {
        reply_ = Rep();
        reply_.error() = error.what();
      } else {
        return;  // nothing to say it with: the client times out
      }
    }
    reply_.client_id() = request.client_id();
    reply_.seq() = request.seq();
    reply_writer_.write(&reply_);
    answered_.fetch_add(1);
    if (slot.has_guid && answered_before(slot)) {
      answered_again_.fetch_add(1);
    }
  }

  // Whether the client of slot had its request slot.seq answered before; then
  // remembers it as that client's last answered one. Only the running handler
  // calls this, so the table needs no lock.
  bool answered_before(const Slot& slot) {
    for (auto& [guid, seq] : last_answered_) {
      if (guid == slot.guid) {
        const bool again = slot.seq <= seq;
        seq = std::max(seq, slot.seq);
        return again;
      }
    }
    last_answered_[last_answered_next_] = {slot.guid, slot.seq};
    last_answered_next_ = (last_answered_next_ + 1) % last_answered_.size();
    return false;
  }

  // A reply that is not the handler's: a probe's (error == nullptr) or an error.
  void answer_aside(const Req& request, const char* error) {
    std::lock_guard lock(aside_mutex_);
    aside_reply_.client_id() = request.client_id();
    aside_reply_.seq() = request.seq();
    if constexpr (HasErrorText<Rep>) {
      aside_reply_.error() = error != nullptr ? error : "";
    }
    reply_writer_.write(&aside_reply_);
  }

  static std::vector<int> free_list(std::size_t capacity) {
    std::vector<int> indices;
    indices.reserve(capacity);
    for (std::size_t i = capacity; i-- > 0;) {
      indices.push_back(static_cast<int>(i));
    }
    return indices;
  }

  // ---- helpers; caller holds mutex_ ----
  bool is_matched(const detail::Guid& guid) const {
    return std::find(matched_.begin(), matched_.end(), guid) != matched_.end();
  }
  // A request of slot's client and sequence number is held, queued or running.
  bool in_progress(const Slot& slot) const {
    if (running_ && running_slot_.seq == slot.seq && running_slot_.guid == slot.guid) {
      return true;
    }
    for (const Slot& other : meta_) {
      if ((other.state == SlotState::held || other.state == SlotState::queued) &&
          other.seq == slot.seq && other.guid == slot.guid) {
        return true;
      }
    }
    return false;
  }
  bool is_gone(const detail::Guid& guid) const {
    return std::find(gone_.begin(), gone_.begin() + static_cast<std::ptrdiff_t>(gone_count_),
                     guid) != gone_.begin() + static_cast<std::ptrdiff_t>(gone_count_);
  }
  static bool expired(std::int64_t deadline_ns) {
    return deadline_ns != 0 && detail::system_now_ns() > deadline_ns;
  }
  void enqueue(int index) {
    meta_[index].state = SlotState::queued;
    ring_[(head_ + queued_) % ring_.size()] = index;
    ++queued_;
  }
  int dequeue() {
    const int index = ring_[head_];
    head_ = (head_ + 1) % ring_.size();
    --queued_;
    return index;
  }
  void release(int index) {
    meta_[index].state = SlotState::free;
    free_.push_back(index);
  }

  std::string service_;
  Handler handler_;
  ServerOptions options_;

  mutable std::mutex mutex_;  // guards the request pool and the client lists
  std::condition_variable wake_;
  std::vector<Req> slots_;
  std::vector<Slot> meta_;
  std::vector<int> free_;
  std::vector<int> ring_;  // queued slot indices, FIFO
  std::size_t head_ = 0;
  std::size_t queued_ = 0;
  bool running_ = false;            // a handler is running
  Slot running_slot_;               // the request it runs
  std::uint64_t held_changes_ = 0;  // +1 per newly held request
  bool stop_ = false;
  std::vector<detail::Guid> matched_;    // client reply readers matched with reply_writer_
  std::array<detail::Guid, 64> gone_{};  // the last reply readers that unmatched
  std::size_t gone_next_ = 0;
  std::size_t gone_count_ = 0;
  ServerStats stats_;

  std::atomic<std::uint64_t> answered_{0};
  std::atomic<std::uint64_t> handler_errors_{0};
  std::atomic<std::uint64_t> answered_again_{0};
  Rep reply_;  // used by the one running handler
  std::array<std::pair<detail::Guid, std::uint64_t>, 64> last_answered_{};  // by the handler
  std::size_t last_answered_next_ = 0;
  std::mutex aside_mutex_;
  Rep aside_reply_;
  Req incoming_;  // written only on the DDS thread that takes requests

  detail::Writer reply_writer_;
  detail::Reader request_reader_;  // destroyed before the writer and the pool
  std::thread worker_;
};

}  // namespace wbi::dds
