// Internal: the samples a reader never got, from the gaps in each writer's
// sequence numbers (every write takes the next one). Fast DDS 2.9's
// sample-lost status misses those its writer declared irrelevant (a GAP sent
// for samples gone from a KEEP_LAST history): 2000 samples sent in a burst
// to a held reader came out received + reported lost = 1660-2000.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <mutex>

#include "wbi/dds/detail/guid.hpp"

namespace wbi::dds::detail {

class SequenceGaps {
 public:
  // Writers followed at once; a further one takes the place of the one heard
  // from least recently (its next sample only starts it again).
  static constexpr std::size_t kWriters = 8;

  // A sample (or a dispose notice) of `writer` with RTPS sequence number
  // `sequence`. The first one heard from a writer starts it: what it wrote
  // before is not counted (a late joiner never asked for it).
  void observe(const Guid& writer, std::uint64_t sequence) {
    std::lock_guard lock(mutex_);
    ++clock_;
    Followed* slot = &writers_[0];
    for (auto& followed : writers_) {
      if (followed.heard != 0 && followed.writer == writer) {
        if (sequence > followed.last + 1) {
          lost_ += sequence - followed.last - 1;
        }
        followed.last = std::max(followed.last, sequence);
        followed.heard = clock_;
        return;
      }
      if (followed.heard < slot->heard) {  // a free slot has heard 0
        slot = &followed;
      }
    }
    *slot = {writer, sequence, clock_};
  }

  std::uint64_t lost() const {
    std::lock_guard lock(mutex_);
    return lost_;
  }

 private:
  struct Followed {
    Guid writer{};
    std::uint64_t last = 0;
    std::uint64_t heard = 0;  // clock_ at its last sample; 0: a free slot
  };
  mutable std::mutex mutex_;  // samples of two writers may arrive on two receive threads
  std::array<Followed, kWriters> writers_{};
  std::uint64_t clock_ = 0;
  std::uint64_t lost_ = 0;
};

}  // namespace wbi::dds::detail
