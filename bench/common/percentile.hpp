// The p-quantile (0 ≤ p ≤ 1) of a set of measurements, nearest rank: what the
// benchmarks report as p50/p99. 0 for an empty set.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace wbi::bench {

inline double percentile(std::vector<double> values, double p) {
  if (values.empty()) {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(p * static_cast<double>(values.size() - 1) + 0.5);
  return values[std::min(index, values.size() - 1)];
}

}  // namespace wbi::bench
