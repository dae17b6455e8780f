#include "wbi/runtime/duration_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wbi::runtime {

void DurationHistogram::clear() {
  std::fill(counts_.begin(), counts_.end(), 0);
  count_ = 0;
  total_ = std::chrono::nanoseconds(0);
}

void DurationHistogram::add(std::chrono::nanoseconds duration) {
  duration = std::max(duration, std::chrono::nanoseconds(0));
  const auto bin = static_cast<std::size_t>(duration / kBinWidth);
  ++counts_[std::min(bin, kBins - 1)];
  ++count_;
  total_ += duration;
}

std::chrono::nanoseconds DurationHistogram::mean() const {
  return count_ > 0 ? total_ / static_cast<std::int64_t>(count_) : std::chrono::nanoseconds(0);
}

std::chrono::nanoseconds DurationHistogram::quantile(double p) const {
  if (count_ == 0) {
    return std::chrono::nanoseconds(0);
  }
  // The rank of the p-quantile among the sorted durations, 1-based.
  const auto rank = static_cast<std::uint64_t>(
                        std::llround(std::clamp(p, 0.0, 1.0) * static_cast<double>(count_ - 1))) +
                    1;
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin < kBins; ++bin) {
    seen += counts_[bin];
    if (seen >= rank) {
      return kBinWidth * static_cast<std::int64_t>(bin + 1);
    }
  }
  return kBinWidth * static_cast<std::int64_t>(kBins);
}

std::string DurationHistogram::mean_and_p99() const {
  using Ms = std::chrono::duration<double, std::milli>;
  char text[64];
  std::snprintf(text, sizeof text, "mean %.3f ms (p99 %.2f ms)", Ms(mean()).count(),
                Ms(quantile(0.99)).count());
  return text;
}

}  // namespace wbi::runtime
