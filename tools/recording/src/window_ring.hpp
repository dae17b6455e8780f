// The memory of a windowed recorder: the newest samples of every topic in one
// fixed block of bytes, so that what it holds can never exceed the bound it
// was given. Each sample is one record, [header | CDR bytes, padded to 8],
// stored contiguously; a record that does not fit before the end of the block
// starts again at its beginning, and the oldest records are evicted to make
// room. push() never allocates.
//
// One reader (the thread that writes a window's file) follows the records
// with a cursor; records evicted before it read them are counted as lost.
// Not thread-safe: the owner serialises push() and read() (WindowRecorder
// holds a mutex for each call, a few microseconds).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
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

// Records copied out of the ring, for writing without holding its lock.
// Capacities are reserved once (max_bytes); reading reuses them.
class RingBatch {
 public:
  explicit RingBatch(std::size_t max_bytes);
  void clear();
  bool append(const RingSample& sample, std::span<const std::uint8_t> bytes);

  struct Entry {
    RingSample sample;
    std::span<const std::uint8_t> bytes;
  };
  std::size_t size() const { return samples_.size(); }
  Entry operator[](std::size_t i) const;
  std::size_t capacity_bytes() const { return bytes_.capacity(); }
  // The memory the batch reserves.
  std::size_t reserved_bytes() const;

 private:
  std::vector<std::uint8_t> bytes_;
  std::vector<RingSample> samples_;
  std::vector<std::size_t> offsets_;
};

class WindowRing {
 public:
  static constexpr std::size_t kHeaderBytes = sizeof(RingSample);
  // The largest sample kept (wbi's messages are far smaller; a camera image
  // would not be).
  static constexpr std::size_t kMaxSampleBytes = std::size_t{1} << 20;

  // capacity_bytes: the whole block (rounded down to 8). keep_ns: how far back
  // the window must reach; evicting a record younger than that (relative to
  // the newest) is counted in evicted_in_window().
  WindowRing(std::size_t capacity_bytes, std::uint64_t keep_ns);
  WindowRing(const WindowRing&) = delete;
  WindowRing& operator=(const WindowRing&) = delete;

  // The bytes one sample takes in the ring.
  static std::size_t record_bytes(std::size_t payload);
  // The largest payload push() accepts: kMaxSampleBytes, and at most a
  // quarter of the block, so that one sample never empties the window.
  std::size_t max_payload() const;

  // Copies the sample in, evicting the oldest records as needed. false (and
  // counted) when it is larger than max_payload().
  bool push(std::uint32_t source, std::uint64_t log_time, std::uint64_t publish_time,
            std::span<const std::uint8_t> bytes);

  // Starts the reader at the oldest record with log time >= from (records
  // older than that are skipped as read() reaches them).
  void start_reading(std::uint64_t from);
  void stop_reading();
  bool reading() const { return reading_; }

  enum class ReadEnd { caught_up, past_until, batch_full };
  // Copies records from the cursor into `out` (cleared first) until the
  // newest one, a record logged after `until` (left for later: a later
  // extension may include it), or `out` is full.
  ReadEnd read(RingBatch& out, std::uint64_t until);

  std::size_t capacity() const { return capacity_; }
  std::size_t used_bytes() const { return used_; }
  std::size_t records() const {
    return static_cast<std::size_t>(next_sequence_ - oldest_sequence_);
  }
  // Log time of the oldest record held; 0 when empty.
  std::uint64_t oldest_log_time() const;
  std::uint64_t pushed() const { return next_sequence_; }
  std::uint64_t pushed_bytes() const { return pushed_bytes_; }
  std::uint64_t too_large() const { return too_large_; }
  std::uint64_t evicted_in_window() const { return evicted_in_window_; }
  std::uint64_t lost_to_reader() const { return lost_to_reader_; }

 private:
  RingSample header_at(std::size_t offset) const;
  void evict_oldest();
  void place(std::size_t offset, const RingSample& sample, std::span<const std::uint8_t> bytes);
  void skip_wrap(std::size_t& offset) const;

  std::unique_ptr<std::uint8_t[]> block_;  // not zeroed: pages are touched as the ring fills
  std::size_t capacity_;
  std::uint64_t keep_ns_;

  // Records lie in [tail_, head_), or, once wrapped, in [tail_, wrap_end_) then [0, head_).
  std::size_t tail_ = 0;
  std::size_t head_ = 0;
  std::size_t wrap_end_ = 0;
  bool wrapped_ = false;
  std::size_t used_ = 0;  // bytes of the records held
  std::uint64_t oldest_sequence_ = 0;
  std::uint64_t next_sequence_ = 0;
  std::uint64_t newest_log_time_ = 0;

  bool reading_ = false;
  std::size_t read_offset_ = 0;  // the record read_sequence_, or head_ when caught up
  std::uint64_t read_sequence_ = 0;
  std::uint64_t read_from_ = 0;

  std::uint64_t pushed_bytes_ = 0;
  std::uint64_t too_large_ = 0;
  std::uint64_t evicted_in_window_ = 0;
  std::uint64_t lost_to_reader_ = 0;
};

}  // namespace wbi::recording
