#include "wbi/estimation/stamp_monitor.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wbi::estimation {

const char* to_string(SampleStatus status) {
  switch (status) {
    case SampleStatus::first:
      return "first";
    case SampleStatus::accepted:
      return "accepted";
    case SampleStatus::after_gap:
      return "after_gap";
    case SampleStatus::duplicated:
      return "duplicated";
    case SampleStatus::out_of_order:
      return "out_of_order";
    case SampleStatus::non_finite:
      return "non_finite";
  }
  return "unknown";
}

StampMonitor::StampMonitor(double sample_rate_hz, double max_gap_s)
    : sample_rate_hz_(sample_rate_hz), max_gap_s_(max_gap_s) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) {
    throw std::invalid_argument("sample-rate must be a positive number of Hz, got " +
                                std::to_string(sample_rate_hz));
  }
  if (!(max_gap_s > 1.5 / sample_rate_hz) || !std::isfinite(max_gap_s)) {
    throw std::invalid_argument("max-gap must exceed 1.5 sample periods (" +
                                std::to_string(1.5 / sample_rate_hz) + " s), got " +
                                std::to_string(max_gap_s));
  }
}

SampleStatus StampMonitor::check(std::int64_t stamp_ns, double& dt_s) {
  dt_s = 0.0;
  if (!has_last_) {
    has_last_ = true;
    last_stamp_ns_ = stamp_ns;
    ++counters_.accepted;
    return SampleStatus::first;
  }
  if (stamp_ns == last_stamp_ns_) {
    ++counters_.duplicated;
    return SampleStatus::duplicated;
  }
  if (stamp_ns < last_stamp_ns_) {
    ++counters_.out_of_order;
    return SampleStatus::out_of_order;
  }
  // Unsigned difference: well defined even for stamps far apart.
  const std::uint64_t interval_ns =
      static_cast<std::uint64_t>(stamp_ns) - static_cast<std::uint64_t>(last_stamp_ns_);
  const double dt = 1e-9 * static_cast<double>(interval_ns);
  last_stamp_ns_ = stamp_ns;
  ++counters_.accepted;
  if (dt > max_gap_s_) {
    ++counters_.gaps;
    return SampleStatus::after_gap;
  }
  const double periods = dt * sample_rate_hz_;
  if (periods > 1.5) {
    counters_.dropped += static_cast<std::uint64_t>(std::llround(periods)) - 1;
  }
  dt_s = dt;
  return SampleStatus::accepted;
}

}  // namespace wbi::estimation
