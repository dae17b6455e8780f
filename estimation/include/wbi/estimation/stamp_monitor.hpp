// Checks the source stamps of a sample stream and counts their anomalies.
// Every filter of this library runs on source stamps (when the sample was taken),
// never on arrival time; this class decides which samples may be used.
#pragma once

#include <cstdint>

namespace wbi::estimation {

// Counts of stamp anomalies since construction (or reset_counters()). A component
// reports them as warnings; a filter never turns them into NaN or a jump.
struct StampCounters {
  std::uint64_t accepted = 0;      // samples used
  std::uint64_t duplicated = 0;    // stamp equal to the last accepted one: sample ignored
  std::uint64_t out_of_order = 0;  // stamp older than the last accepted one: sample ignored
  std::uint64_t dropped = 0;       // samples missing, inferred from intervals > 1.5 periods
  std::uint64_t gaps = 0;          // intervals > max_gap: the filter restarted
  std::uint64_t non_finite = 0;    // NaN or infinity in the values: sample ignored

  // Duplicated and out-of-order stamps: the stamps that did not increase.
  std::uint64_t non_increasing() const { return duplicated + out_of_order; }
  std::uint64_t anomalies() const { return non_increasing() + dropped + gaps + non_finite; }
  StampCounters& operator+=(const StampCounters& other) {
    accepted += other.accepted;
    duplicated += other.duplicated;
    out_of_order += other.out_of_order;
    dropped += other.dropped;
    gaps += other.gaps;
    non_finite += other.non_finite;
    return *this;
  }
};

// What happened to one sample.
enum class SampleStatus {
  first,         // first sample since construction or reset(): filter initialised
  accepted,      // normal sample, dt > 0
  after_gap,     // interval longer than max_gap: filter restarted from this sample
  duplicated,    // ignored, outputs unchanged
  out_of_order,  // ignored, outputs unchanged
  non_finite,    // ignored, outputs unchanged
};

// True when the sample was used (first, accepted or after_gap).
constexpr bool used(SampleStatus status) {
  return status == SampleStatus::first || status == SampleStatus::accepted ||
         status == SampleStatus::after_gap;
}

const char* to_string(SampleStatus status);

class StampMonitor {
 public:
  // sample_rate_hz: nominal rate, used only to count dropped samples.
  // max_gap_s: longer intervals restart the filter. Throws std::invalid_argument
  // unless sample_rate_hz > 0 and max_gap_s > 1.5 / sample_rate_hz.
  StampMonitor(double sample_rate_hz, double max_gap_s);

  // Classifies stamp_ns against the last accepted stamp. For a used sample the
  // stamp becomes the last accepted one and dt_s is the interval in seconds
  // (0 for first and after_gap).
  SampleStatus check(std::int64_t stamp_ns, double& dt_s);
  // Counts a sample rejected before its stamp was looked at.
  void count_non_finite() { ++counters_.non_finite; }

  // Forgets the last stamp: the next sample is `first`. Counters are kept.
  void reset() { has_last_ = false; }
  void reset_counters() { counters_ = StampCounters{}; }

  const StampCounters& counters() const { return counters_; }
  double sample_rate_hz() const { return sample_rate_hz_; }
  double max_gap_s() const { return max_gap_s_; }

 private:
  double sample_rate_hz_;
  double max_gap_s_;
  bool has_last_ = false;
  std::int64_t last_stamp_ns_ = 0;
  StampCounters counters_;
};

}  // namespace wbi::estimation
