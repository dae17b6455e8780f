// Shared helpers of the estimation tests: feeding functions of time.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "wbi/estimation/estimator_factory.hpp"

namespace wbi::estimation::test {

// Every method with its defaults, one estimator each.
inline std::vector<std::string> all_methods() { return method_names(); }

// Stamp of sample k at 1 kHz, in ns.
inline std::int64_t stamp_at(std::int64_t k) { return k * 1'000'000; }

inline double seconds(std::int64_t stamp_ns) { return 1e-9 * static_cast<double>(stamp_ns); }

// Feeds q(t) (same value on every joint, scaled by joint index + 1) at the given stamps.
inline void feed(DerivativeEstimator& estimator, const std::vector<std::int64_t>& stamps,
                 const std::function<double(double)>& q_of_t) {
  Eigen::VectorXd q(estimator.joints());
  for (const std::int64_t stamp : stamps) {
    for (Eigen::Index j = 0; j < q.size(); ++j) {
      q(j) = static_cast<double>(j + 1) * q_of_t(seconds(stamp));
    }
    estimator.update(stamp, q);
  }
}

// Stamps 0, 1, ..., n-1 ms.
inline std::vector<std::int64_t> regular_stamps(std::int64_t n) {
  std::vector<std::int64_t> stamps;
  for (std::int64_t k = 0; k < n; ++k) {
    stamps.push_back(stamp_at(k));
  }
  return stamps;
}

// Stamps with some samples missing and some jitter, strictly increasing.
inline std::vector<std::int64_t> irregular_stamps(std::int64_t n) {
  std::vector<std::int64_t> stamps;
  for (std::int64_t k = 0; k < n; ++k) {
    if (k % 7 == 3 || k % 11 == 5) {
      continue;  // dropped
    }
    stamps.push_back(stamp_at(k) + (k % 3) * 50'000);  // ±50 µs jitter
  }
  return stamps;
}

}  // namespace wbi::estimation::test
