// The memory of a windowed recorder: the newest samples of every topic in one
// fixed block of bytes, so that what it holds can never exceed the bound it
// was given. Each sample is one record, [header | CDR bytes, padded to 32],
// stored contiguously; a record that does not fit before the end of the block
// starts again at its beginning, and the oldest records are evicted to make
// room. push() never allocates.
//
// Pushers (the DDS callbacks) take a mutex among themselves; the one reader
// (the thread that writes a window's file) never does, so a reader that is
// preempted or slow never holds up a DDS thread. It reads as a seqlock
// reader does: it copies a record, then checks that the record had not been
// evicted meanwhile (a pusher counts an eviction before it writes over the
// bytes: release fence; the reader copies, then acquire fence, then looks at
// the count). Records evicted before the reader got to them are counted as
// lost. The reader's racy copy is validated, never trusted: the idiom of
// seqlocks (as in the Linux kernel), outside what ThreadSanitizer accepts.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace wbi::recording {

// One record's description, as stored before its bytes.
struct RingSample {
  std::uint64_t sequence = 0;  // 0, 1, 2, ... in push order
  std::uint64_t log_time = 0;  // ns, system time at arrival
  std::uint64_t publish_time = 0;
  std::uint32_t source = 0;  // the recorder's topic index
  std::uint32_t size = 0;    // CDR bytes that follow
};

// Records copied out of the ring, for writing. Capacities are reserved once
// (max_bytes); reading reuses them.
class RingBatch {
 public:
  explicit RingBatch(std::size_t max_bytes);
  void clear();
  bool append(const RingSample& sample, std::span<const std::uint8_t> bytes);
  void pop_back();

  struct Entry {
    RingSample sample;
    std::span<const std::uint8_t> bytes;
  };
  std::size_t size() const { return samples_.size(); }
  Entry operator[](std::size_t i) const;
  // The memory the batch reserves.
  std::size_t reserved_bytes() const;

 private:
  std::vector<std::uint8_t> bytes_;
  std::vector<RingSample> samples_;
  std::vector<std::size_t> offsets_;
};

// What the ring holds and has seen (a consistent snapshot).
struct RingStats {
  std::uint64_t pushed = 0;
  std::uint64_t pushed_bytes = 0;  // record bytes, headers included
  std::size_t used_bytes = 0;
  std::size_t records = 0;
  std::uint64_t oldest_log_time = 0;  // 0: empty
  std::uint64_t too_large = 0;
  std::uint64_t evicted_in_window = 0;
};

class WindowRing {
 public:
  static constexpr std::size_t kHeaderBytes = sizeof(RingSample);
  static constexpr std::size_t kAlignment = 32;  // records start on it: a header always fits
  // The largest sample kept (the writer copies at most that much at once):
  // wbi's messages are far smaller (a 32-joint SensorSample is 0.8 kB); a
  // camera image would not be.
  static constexpr std::size_t kMaxSampleBytes = std::size_t{256} << 10;

  // capacity_bytes: the whole block (rounded down to 32). keep_ns: how far
  // back the window must reach; evicting a record younger than that
  // (relative to the newest) is counted in evicted_in_window.
  WindowRing(std::size_t capacity_bytes, std::uint64_t keep_ns);
  WindowRing(const WindowRing&) = delete;
  WindowRing& operator=(const WindowRing&) = delete;

  // The bytes one sample takes in the ring.
  static std::size_t record_bytes(std::size_t payload);
  // kMaxSampleBytes, and at most a quarter of the block, so that one sample
  // never empties the window.
  std::size_t max_payload() const;

  // Any thread. Copies the sample in, evicting the oldest records as needed;
  // false (and counted) when it is larger than max_payload().
  bool push(std::uint32_t source, std::uint64_t log_time, std::uint64_t publish_time,
            std::span<const std::uint8_t> bytes);

  // --- the reader (one thread) ---
  // Starts at the oldest record with log time >= from (older ones are
  // skipped as read() reaches them).
  void start_reading(std::uint64_t from);
  void stop_reading() { reading_ = false; }
  bool reading() const { return reading_; }

  enum class ReadEnd { caught_up, past_until, batch_full };
  // Copies records from the cursor into `out` (cleared first) until the
  // newest one, a record logged after `until` (left for later: a later
  // extension may include it), or `out` is full.
  ReadEnd read(RingBatch& out, std::uint64_t until);
  // Records evicted before the reader copied them.
  std::uint64_t lost_to_reader() const { return lost_to_reader_; }

  RingStats stats() const;
  std::size_t capacity() const { return capacity_; }

 private:
  RingSample header_at(std::size_t offset) const;
  void evict_oldest();
  // The reader's record `sequence` had not been evicted when this returns true
  // (so every byte copied of it before the call was the record's).
  bool still_held(std::uint64_t sequence) const;
  void resync();

  std::unique_ptr<std::uint8_t[]> block_;  // not zeroed: pages are touched as the ring fills
  std::size_t capacity_;
  std::uint64_t keep_ns_;

  // Pushers' state (mutex_). Records lie in [tail_, head_), or, once wrapped,
  // in [tail_, wrap_end_) then [0, head_).
  mutable std::mutex mutex_;
  std::size_t tail_ = 0;
  std::size_t head_ = 0;
  std::size_t wrap_end_ = 0;
  bool wrapped_ = false;
  std::size_t used_ = 0;
  std::uint64_t newest_log_time_ = 0;
  std::uint64_t pushed_bytes_ = 0;
  std::uint64_t too_large_ = 0;
  std::uint64_t evicted_in_window_ = 0;
  // Published to the reader: records [oldest, next) are held and whole.
  std::atomic<std::uint64_t> oldest_sequence_{0};
  std::atomic<std::uint64_t> next_sequence_{0};

  // Reader's state (its thread only).
  bool reading_ = false;
  std::size_t read_offset_ = 0;
  std::uint64_t read_sequence_ = 0;
  std::uint64_t read_from_ = 0;
  std::uint64_t lost_to_reader_ = 0;
};

}  // namespace wbi::recording
