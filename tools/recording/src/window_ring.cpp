#include "window_ring.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace wbi::recording {

namespace {

constexpr std::size_t kAlignment = 8;
// A batch holds at most one entry per this many bytes of its capacity
// (entries of tiny samples would otherwise need unbounded room).
constexpr std::size_t kBatchBytesPerEntry = 64;

std::size_t round_up(std::size_t n) { return (n + kAlignment - 1) / kAlignment * kAlignment; }

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

std::uint64_t WindowRing::oldest_log_time() const {
  return records() == 0 ? 0 : header_at(tail_).log_time;
}

void WindowRing::skip_wrap(std::size_t& offset) const {
  if (wrapped_ && offset == wrap_end_) {
    offset = 0;
  }
}

void WindowRing::evict_oldest() {
  const RingSample oldest = header_at(tail_);
  if (newest_log_time_ < oldest.log_time + keep_ns_) {
    ++evicted_in_window_;  // the window reaches back less far than it should
  }
  const std::size_t bytes = record_bytes(oldest.size);
  tail_ += bytes;
  used_ -= bytes;
  ++oldest_sequence_;
  skip_wrap(tail_);
  if (tail_ == 0 && wrapped_) {
    wrapped_ = false;
  }
  if (records() == 0) {
    tail_ = head_ = 0;
    wrapped_ = false;
  }
  if (reading_ && read_sequence_ < oldest_sequence_) {
    ++lost_to_reader_;
    read_sequence_ = oldest_sequence_;
    read_offset_ = records() == 0 ? head_ : tail_;
  }
}

void WindowRing::place(std::size_t offset, const RingSample& sample,
                       std::span<const std::uint8_t> bytes) {
  std::memcpy(block_.get() + offset, &sample, kHeaderBytes);
  if (!bytes.empty()) {
    std::memcpy(block_.get() + offset + kHeaderBytes, bytes.data(), bytes.size());
  }
}

bool WindowRing::push(std::uint32_t source, std::uint64_t log_time, std::uint64_t publish_time,
                      std::span<const std::uint8_t> bytes) {
  if (bytes.size() > max_payload()) {
    ++too_large_;
    return false;
  }
  const std::size_t bytes_needed = record_bytes(bytes.size());
  for (;;) {
    if (!wrapped_) {
      if (capacity_ - head_ >= bytes_needed) {
        break;
      }
      // Not enough room before the end of the block: go on at its beginning.
      wrap_end_ = head_;
      head_ = 0;
      wrapped_ = true;
      if (reading_ && read_sequence_ == next_sequence_) {
        read_offset_ = 0;
      }
    } else if (tail_ - head_ >= bytes_needed) {
      break;
    } else {
      evict_oldest();
    }
  }
  place(head_,
        {next_sequence_, log_time, publish_time, source, static_cast<std::uint32_t>(bytes.size())},
        bytes);
  head_ += bytes_needed;
  used_ += bytes_needed;
  ++next_sequence_;
  pushed_bytes_ += bytes_needed;
  newest_log_time_ = std::max(newest_log_time_, log_time);
  return true;
}

void WindowRing::start_reading(std::uint64_t from) {
  reading_ = true;
  read_sequence_ = oldest_sequence_;
  read_offset_ = records() == 0 ? head_ : tail_;
  read_from_ = from;
}

void WindowRing::stop_reading() { reading_ = false; }

WindowRing::ReadEnd WindowRing::read(RingBatch& out, std::uint64_t until) {
  out.clear();
  // Skipping old records is cheap but not free: bound the time under the lock.
  constexpr std::size_t kMaxSkipsPerRead = 65536;
  std::size_t skipped = 0;
  while (read_sequence_ < next_sequence_) {
    const RingSample sample = header_at(read_offset_);
    if (read_from_ != 0 && sample.log_time < read_from_) {
      if (++skipped == kMaxSkipsPerRead) {
        return ReadEnd::batch_full;
      }
    } else {
      read_from_ = 0;  // the window has begun: later records are all taken
      if (sample.log_time > until) {
        return ReadEnd::past_until;
      }
      if (!out.append(sample, {block_.get() + read_offset_ + kHeaderBytes, sample.size})) {
        return ReadEnd::batch_full;
      }
    }
    read_offset_ += record_bytes(sample.size);
    ++read_sequence_;
    skip_wrap(read_offset_);
  }
  return ReadEnd::caught_up;
}

}  // namespace wbi::recording
