// Estimated joint torques against true ones, for launch tests of the F/T-based
// torque estimation (estimation/wrenches/README.md).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <vector>

namespace wbi::test {

// Estimated joint torques against true ones (sensed, or the ground truth's
// applied torques) of the same source stamp, summed once settled. The streams
// are best effort: either side may miss some samples.
class TorqueComparison {
 public:
  struct Figures {
    std::size_t matched = 0;
    std::size_t external_wrenches = 0;
    double rmse = 0.0;  // [N·m] over every joint
    double rms = 0.0;   // [N·m] of the true torques
  };

  void truth(std::int64_t stamp_ns, const std::vector<double>& tau) {
    std::lock_guard lock(mutex_);
    truth_[stamp_ns] = tau;
    if (truth_.size() > 4000) {
      truth_.erase(truth_.begin());
    }
  }

  void estimated(std::int64_t stamp_ns, const std::vector<double>& tau, std::size_t wrenches) {
    std::lock_guard lock(mutex_);
    first_ns_ = first_ns_ == 0 ? stamp_ns : first_ns_;
    external_wrenches_ = wrenches;
    const auto found = truth_.find(stamp_ns);
    if (found == truth_.end() || found->second.size() != tau.size() ||
        stamp_ns - first_ns_ < 1'500'000'000) {
      return;
    }
    for (std::size_t j = 0; j < tau.size(); ++j) {
      error_ += (tau[j] - found->second[j]) * (tau[j] - found->second[j]);
      square_ += found->second[j] * found->second[j];
      ++values_;
    }
    ++matched_;
  }

  Figures figures() const {
    std::lock_guard lock(mutex_);
    const double n = std::max<double>(1.0, static_cast<double>(values_));
    return {matched_, external_wrenches_, std::sqrt(error_ / n), std::sqrt(square_ / n)};
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::int64_t, std::vector<double>> truth_;
  std::int64_t first_ns_ = 0;
  std::size_t matched_ = 0, values_ = 0, external_wrenches_ = 0;
  double error_ = 0.0, square_ = 0.0;
};

}  // namespace wbi::test
