#include "heartbeats.hpp"

#include <wbi/dds/topics.hpp>

namespace wbi::launch {

Heartbeats::Heartbeats(dds::Participant& participant)
    : status_(participant, dds::topics::kStatus, dds::qos::kStatus,
              [this](const wbi::msg::ComponentStatus& status, const dds::detail::SampleInfo&) {
                std::lock_guard lock(mutex_);
                heard_[status.instance().to_string()] = Clock::now();
              }) {}

std::optional<Heartbeats::Clock::time_point> Heartbeats::newest(
    const std::vector<std::string>& instances) const {
  std::lock_guard lock(mutex_);
  std::optional<Clock::time_point> newest;
  for (const auto& instance : instances) {
    if (const auto it = heard_.find(instance); it != heard_.end()) {
      newest = newest ? std::max(*newest, it->second) : it->second;
    }
  }
  return newest;
}

void Heartbeats::forget(const std::vector<std::string>& instances) {
  std::lock_guard lock(mutex_);
  for (const auto& instance : instances) {
    heard_.erase(instance);
  }
}

}  // namespace wbi::launch
