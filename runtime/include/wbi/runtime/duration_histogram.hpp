// Durations of a loop's parts (a robot's tick, a component's cycle) for an end-of-run line: count,
// mean and a quantile, from fixed bins (10 µs wide up to 100 ms, one bin beyond), so that adding
// one in the loop never allocates.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

namespace wbi::runtime {

class DurationHistogram {
 public:
  static constexpr std::chrono::nanoseconds kBinWidth{10'000};
  static constexpr std::size_t kBins = 10'000;  // the last one holds every longer duration

  DurationHistogram() : counts_(kBins, 0) {}

  void clear();
  void add(std::chrono::nanoseconds duration);
  std::uint64_t count() const { return count_; }
  std::chrono::nanoseconds mean() const;
  // The upper edge of the bin of the p-quantile (nearest rank, 0 ≤ p ≤ 1): a
  // bound within kBinWidth. 0 when empty; at least 100 ms in the last bin.
  std::chrono::nanoseconds quantile(double p) const;
  // "mean 0.307 ms (p99 0.52 ms)", the words of the end-of-run lines.
  std::string mean_and_p99() const;

 private:
  std::vector<std::uint64_t> counts_;
  std::uint64_t count_ = 0;
  std::chrono::nanoseconds total_{0};
};

}  // namespace wbi::runtime
