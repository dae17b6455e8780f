// Internal: the decision behind ProducerPolicy::one (wbi/dds/producers.hpp),
// free of DDS so that it is tested on given writers and times.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "wbi/dds/detail/endpoints.hpp"
#include "wbi/dds/producers.hpp"

namespace wbi::dds::detail {

class ProducerBinding {
 public:
  // Foreign writers remembered by name; more are dropped and counted alike.
  static constexpr std::size_t kRememberedWriters = 16;

  enum class Verdict {
    take,           // the bound writer, or the first one heard: bound now
    rebound,        // the bound writer was gone: this one is bound now
    first_foreign,  // dropped: the first sample of this foreign writer
    foreign,        // dropped
  };

  // A sample of `writer` arrived at now_ns (steady clock). `ended(guid)` says
  // whether the process of a writer (the bound one, or the owner) is known to
  // have ended; it is called at most once per new writer, when that writer is
  // first heard. On a rebind, `previous` is set to the writer that was bound.
  //
  // owner (ProducerPolicy::owner): nullptr for none; else the writer whose
  // participant's writer is the one taken, all zero while not known yet.
  template <class Ended>
  Verdict admit(const Guid& writer, std::int64_t now_ns, Ended&& ended, Guid& previous,
                const Guid* owner = nullptr) {
    std::lock_guard lock(mutex_);
    previous = bound_;
    if (owner != nullptr) {
      return admit_owned(writer, now_ns, *owner, ended);
    }
    if (bound_ == writer && has_bound_) {
      last_bound_ns_ = now_ns;
      return Verdict::take;
    }
    if (!has_bound_) {
      bind(writer, now_ns);
      return Verdict::take;
    }
    Foreign* known = find(writer);
    if (known == nullptr) {
      // New writer: the bound one's successor if the bound one is gone.
      if (bound_left_ || (!full() && ended(bound_))) {
        rebind(writer, now_ns);
        return Verdict::rebound;
      }
      return drop_foreign(writer, now_ns);
    }
    if (bound_left_ && known->first_heard_ns > last_bound_ns_) {
      forget(*known);
      rebind(writer, now_ns);
      return Verdict::rebound;
    }
    ++counts_.foreign_samples;
    return Verdict::foreign;
  }

  static bool same_participant(const Guid& a, const Guid& b) {
    return std::equal(a.begin(), a.begin() + 12, b.begin());
  }

  // DDS unmatched `writer` (its participant left or its lease expired).
  void on_unmatched(const Guid& writer) {
    std::lock_guard lock(mutex_);
    if (has_bound_ && bound_ == writer) {
      bound_left_ = true;
    } else if (Foreign* known = find(writer)) {
      forget(*known);
    }
  }

  ProducerCounts counts() const {
    std::lock_guard lock(mutex_);
    return counts_;
  }
  Guid bound() const {
    std::lock_guard lock(mutex_);
    return bound_;
  }

 private:
  struct Foreign {
    Guid writer{};
    std::int64_t first_heard_ns = 0;
    bool used = false;
  };

  // The writer of the owner's participant is taken, whichever it is now (the
  // owner's reader moves on its own rules); every other writer is foreign.
  //
  // Before the owner is heard (a robot's sensors can arrive before its latched
  // description), the first writer is taken, provisionally: dropping its
  // samples would lose a lockstep robot's first tick. Once the owner is known,
  // a provisional writer of another participant is foreign. The same once the
  // owner's process has ended (a restarted robot's first sensor sample can
  // come before its description moves the owner): the first new writer is
  // taken until the owner moves on. `ended` is asked once per new writer.
  template <class Ended>
  Verdict admit_owned(const Guid& writer, std::int64_t now_ns, const Guid& owner, Ended& ended) {
    if (owner == Guid{}) {
      if (!has_bound_) {
        bind(writer, now_ns);
        return Verdict::take;
      }
      if (bound_ == writer) {
        last_bound_ns_ = now_ns;
        return Verdict::take;
      }
      return drop_foreign(writer, now_ns);
    }
    if (same_participant(writer, owner)) {
      if (has_bound_ && bound_ == writer) {
        last_bound_ns_ = now_ns;
        return Verdict::take;
      }
      if (Foreign* known = find(writer)) {
        forget(*known);  // foreign under the owner before
      }
      return take_over(writer, now_ns);
    }
    if (owner == ended_owner_ && has_bound_ && bound_ == writer) {
      last_bound_ns_ = now_ns;
      return Verdict::take;
    }
    if (owner != ended_owner_ && find(writer) == nullptr && !full() && ended(owner)) {
      ended_owner_ = owner;
      return take_over(writer, now_ns);
    }
    return drop_foreign(writer, now_ns);
  }

  Verdict drop_foreign(const Guid& writer, std::int64_t now_ns) {
    ++counts_.foreign_samples;
    if (find(writer) != nullptr) {
      return Verdict::foreign;
    }
    if (!full()) {
      remember(writer, now_ns);
      return Verdict::first_foreign;
    }
    // 16 foreign writers on one topic is an attack or a misconfigured
    // network, not a restart: the others are counted, said once, not named.
    if (overflow_said_) {
      return Verdict::foreign;
    }
    overflow_said_ = true;
    ++counts_.foreign_writers;
    return Verdict::first_foreign;
  }

  void bind(const Guid& writer, std::int64_t now_ns) {
    bound_ = writer;
    has_bound_ = true;
    bound_left_ = false;
    last_bound_ns_ = now_ns;
    counts_.bound = writer;
  }
  void rebind(const Guid& writer, std::int64_t now_ns) {
    bind(writer, now_ns);
    ++counts_.rebinds;
  }
  // `writer` is taken from now on: a first binding, or a rebind.
  Verdict take_over(const Guid& writer, std::int64_t now_ns) {
    if (!has_bound_) {
      bind(writer, now_ns);
      return Verdict::take;
    }
    rebind(writer, now_ns);
    return Verdict::rebound;
  }
  Foreign* find(const Guid& writer) {
    for (auto& foreign : foreign_) {
      if (foreign.used && foreign.writer == writer) {
        return &foreign;
      }
    }
    return nullptr;
  }
  bool full() const {
    for (const auto& foreign : foreign_) {
      if (!foreign.used) {
        return false;
      }
    }
    return true;
  }
  void remember(const Guid& writer, std::int64_t now_ns) {
    ++counts_.foreign_writers;
    for (auto& foreign : foreign_) {
      if (!foreign.used) {
        foreign = {writer, now_ns, true};
        return;
      }
    }
  }
  static void forget(Foreign& foreign) { foreign.used = false; }

  mutable std::mutex mutex_;
  Guid bound_{};
  bool has_bound_ = false;
  bool bound_left_ = false;         // DDS unmatched the bound writer
  std::int64_t last_bound_ns_ = 0;  // its last sample
  std::array<Foreign, kRememberedWriters> foreign_{};
  bool overflow_said_ = false;
  Guid ended_owner_{};  // an owner whose process had ended when a new writer came
  ProducerCounts counts_;
};

}  // namespace wbi::dds::detail
