#include "window_ring.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace wbi::recording {

namespace {

// A batch holds at most one entry per this many bytes of its capacity
// (entries of tiny samples would otherwise need unbounded room).
constexpr std::size_t kBatchBytesPerEntry = 64;

std::size_t round_up(std::size_t n) {
  return (n + WindowRing::kAlignment - 1) / WindowRing::kAlignment * WindowRing::kAlignment;
}

}  // namespace

RingBatch::RingBatch(std::size_t max_bytes) {
  bytes_.reserve(max_bytes);
  samples_.reserve(max_bytes / kBatchBytesPerEntry);
  offsets_.reserve(max_bytes / kBatchBytesPerEntry);
}

void RingBatch::clear() {
  bytes_.clear();
  samples_.clear();
  offsets_.clear();
}

bool RingBatch::append(const RingSample& sample, std::span<const std::uint8_t> bytes) {
  if (bytes_.size() + bytes.size() > bytes_.capacity() || samples_.size() == samples_.capacity()) {
    return false;
  }
  offsets_.push_back(bytes_.size());
  samples_.push_back(sample);
  bytes_.insert(bytes_.end(), bytes.begin(), bytes.end());
  return true;
}

void RingBatch::pop_back() {
  bytes_.resize(offsets_.back());
  offsets_.pop_back();
  samples_.pop_back();
}

RingBatch::Entry RingBatch::operator[](std::size_t i) const {
  return {samples_[i], std::span(bytes_).subspan(offsets_[i], samples_[i].size)};
}

std::size_t RingBatch::reserved_bytes() const {
  return bytes_.capacity() + samples_.capacity() * sizeof(RingSample) +
         offsets_.capacity() * sizeof(std::size_t);
}

WindowRing::WindowRing(std::size_t capacity_bytes, std::uint64_t keep_ns)
    : capacity_(capacity_bytes / kAlignment * kAlignment), keep_ns_(keep_ns) {
  if (capacity_ < 4 * record_bytes(0)) {
    throw std::invalid_argument("window ring of " + std::to_string(capacity_bytes) +
                                " bytes is too small");
  }
  block_.reset(new std::uint8_t[capacity_]);  // NOLINT: deliberately uninitialised
}

std::size_t WindowRing::record_bytes(std::size_t payload) {
  return kHeaderBytes + round_up(payload);
}

std::size_t WindowRing::max_payload() const {
  return std::min(capacity_ / 4 - kHeaderBytes, kMaxSampleBytes);
}

RingSample WindowRing::header_at(std::size_t offset) const {
  RingSample sample;
  std::memcpy(&sample, block_.get() + offset, kHeaderBytes);
  return sample;
}

// --- pushers (mutex_) ----------------------------------------------------

void WindowRing::evict_oldest() {
  const RingSample oldest = header_at(tail_);
  if (newest_log_time_ < oldest.log_time + keep_ns_) {
    ++evicted_in_window_;  // the window reaches back less far than it should
  }
  const std::size_t bytes = record_bytes(oldest.size);
  tail_ += bytes;
  used_ -= bytes;
  oldest_sequence_.store(oldest.sequence + 1, std::memory_order_relaxed);
  if (wrapped_ && tail_ == wrap_end_) {
    tail_ = 0;
    wrapped_ = false;
  }
}

bool WindowRing::push(std::uint32_t source, std::uint64_t log_time, std::uint64_t publish_time,
                      std::span<const std::uint8_t> bytes) {
  std::lock_guard lock(mutex_);
  if (bytes.size() > max_payload()) {
    ++too_large_;
    return false;
  }
  const std::size_t bytes_needed = record_bytes(bytes.size());
  const std::uint64_t sequence = next_sequence_.load(std::memory_order_relaxed);
  for (;;) {
    if (!wrapped_) {
      if (capacity_ - head_ >= bytes_needed) {
        break;
      }
      // Not enough room before the end of the block: go on at its beginning.
      wrap_end_ = head_;
      head_ = 0;
      wrapped_ = true;
    } else if (tail_ - head_ >= bytes_needed) {
      break;
    } else if (sequence == oldest_sequence_.load(std::memory_order_relaxed)) {
      tail_ = 0;  // empty: every record was evicted, the block is free from its start
      wrapped_ = false;
    } else {
      evict_oldest();
    }
  }
  // Evictions are published before their bytes are written over (seqlock writer side).
  std::atomic_thread_fence(std::memory_order_release);
  const RingSample header{sequence, log_time, publish_time, source,
                          static_cast<std::uint32_t>(bytes.size())};
  std::memcpy(block_.get() + head_, &header, kHeaderBytes);
  if (!bytes.empty()) {
    std::memcpy(block_.get() + head_ + kHeaderBytes, bytes.data(), bytes.size());
  }
  head_ += bytes_needed;
  used_ += bytes_needed;
  pushed_bytes_ += bytes_needed;
  newest_log_time_ = std::max(newest_log_time_, log_time);
  next_sequence_.store(sequence + 1, std::memory_order_release);
  return true;
}

RingStats WindowRing::stats() const {
  std::lock_guard lock(mutex_);
  RingStats stats;
  stats.pushed = next_sequence_.load(std::memory_order_relaxed);
  stats.pushed_bytes = pushed_bytes_;
  stats.used_bytes = used_;
  stats.records =
      static_cast<std::size_t>(stats.pushed - oldest_sequence_.load(std::memory_order_relaxed));
  stats.oldest_log_time = stats.records == 0 ? 0 : header_at(tail_).log_time;
  stats.too_large = too_large_;
  stats.evicted_in_window = evicted_in_window_;
  return stats;
}

// --- the reader ------------------------------------------------------------

bool WindowRing::still_held(std::uint64_t sequence) const {
  std::atomic_thread_fence(std::memory_order_acquire);  // after the copy (seqlock reader side)
  return oldest_sequence_.load(std::memory_order_relaxed) <= sequence;
}

void WindowRing::resync() {
  std::lock_guard lock(mutex_);
  const std::uint64_t oldest = oldest_sequence_.load(std::memory_order_relaxed);
  if (read_sequence_ < oldest) {
    lost_to_reader_ += oldest - read_sequence_;
    read_sequence_ = oldest;
  }
  // Walk from the oldest record to the reader's (the pushers wait meanwhile:
  // only after an overrun).
  std::size_t offset = tail_;
  for (std::uint64_t sequence = oldest; sequence < read_sequence_; ++sequence) {
    offset += record_bytes(header_at(offset).size);
    if (wrapped_ && offset == wrap_end_) {
      offset = 0;
    }
  }
  read_offset_ = offset;
}

void WindowRing::start_reading(std::uint64_t from) {
  std::lock_guard lock(mutex_);
  reading_ = true;
  read_sequence_ = oldest_sequence_.load(std::memory_order_relaxed);
  read_offset_ = tail_;
  read_from_ = from;
}

WindowRing::ReadEnd WindowRing::read(RingBatch& out, std::uint64_t until) {
  out.clear();
  while (read_sequence_ < next_sequence_.load(std::memory_order_acquire)) {
    if (read_offset_ == capacity_) {
      read_offset_ = 0;
    }
    const RingSample sample = header_at(read_offset_);
    if (sample.sequence != read_sequence_) {
      // Not here: the pushers went on at the block's beginning (or the record
      // was evicted and written over; then it is lost).
      if (!still_held(read_sequence_) || read_offset_ == 0) {
        resync();
      } else {
        read_offset_ = 0;
      }
      continue;
    }
    const bool fits =
        sample.size <= max_payload() && read_offset_ + record_bytes(sample.size) <= capacity_;
    const bool skipped = read_from_ != 0 && sample.log_time < read_from_;
    const bool copied =
        fits && !skipped && sample.log_time <= until &&
        out.append(sample, {block_.get() + read_offset_ + kHeaderBytes, sample.size});
    if (!still_held(read_sequence_) || !fits) {
      if (copied) {
        out.pop_back();  // its bytes may be another record's
      }
      resync();
      continue;
    }
    if (!skipped) {
      read_from_ = 0;  // the window has begun: later records are all taken
      if (sample.log_time > until) {
        return ReadEnd::past_until;
      }
      if (!copied) {
        return ReadEnd::batch_full;
      }
    }
    read_offset_ += record_bytes(sample.size);
    ++read_sequence_;
  }
  return ReadEnd::caught_up;
}

}  // namespace wbi::recording
