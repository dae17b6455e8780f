#include "wbi/runtime/status_report.hpp"

#include <algorithm>
#include <stdexcept>

namespace wbi::runtime {

StatusCounter& StatusReport::counter(std::string_view name) {
  if (name.empty()) {
    throw std::invalid_argument("status report: a counter needs a name");
  }
  std::lock_guard lock(registration_);
  const std::size_t n = count_.load(std::memory_order_relaxed);
  for (std::size_t i = 0; i < n; ++i) {
    if (entries_[i].name == name) {
      return entries_[i].counter;
    }
  }
  if (n == kMaxCounters) {
    throw std::invalid_argument("status report: cannot add counter '" + std::string(name) +
                                "': at most " + std::to_string(kMaxCounters) + " counters");
  }
  entries_[n].name = name;
  count_.store(n + 1, std::memory_order_release);  // readers see the name before the count
  return entries_[n].counter;
}

void StatusReport::set_error(std::string_view text) {
  {
    std::lock_guard lock(error_mutex_);
    const std::size_t length = std::min(text.size(), kMaxErrorLength);
    std::copy_n(text.data(), length, error_.begin());
    error_[length] = '\0';
  }
  errors_.fetch_add(1, std::memory_order_release);
}

std::string StatusReport::last_error() const {
  std::string out;
  last_error_into(out);
  return out;
}

}  // namespace wbi::runtime
