#include "heartbeats.hpp"

#include <wbi/dds/topics.hpp>

namespace wbi::launch {

Heartbeats::Heartbeats(dds::Participant& participant)
    : status_(participant, dds::topics::kStatus, dds::qos::kStatus,
              [this](const wbi::msg::ComponentStatus& status, const dds::detail::SampleInfo&) {
                const auto now = Clock::now();
                const bool periodic =
                    status.rate_hz() > 0.0 && status.state() == wbi::msg::LifecycleState::ACTIVE;
                std::lock_guard lock(mutex_);
                const auto [it, first] = heard_.try_emplace(status.instance().to_string());
                Heard& heard = it->second;
                heard.at = now;
                if (!periodic) {
                  heard.looping = false;
                } else if (first || status.iterations() != heard.iterations) {
                  heard.looping = heard.looping || !first;
                  heard.advanced_at = now;
                }
                heard.iterations = status.iterations();
              }) {}

std::optional<Heartbeats::Clock::time_point> Heartbeats::newest(
    const std::vector<std::string>& instances) const {
  std::lock_guard lock(mutex_);
  std::optional<Clock::time_point> newest;
  for (const auto& instance : instances) {
    if (const auto it = heard_.find(instance); it != heard_.end()) {
      newest = newest ? std::max(*newest, it->second.at) : it->second.at;
    }
  }
  return newest;
}

std::optional<Heartbeats::StalledLoop> Heartbeats::stalled_loop(
    const std::vector<std::string>& instances, Clock::duration timeout) const {
  std::lock_guard lock(mutex_);
  std::optional<StalledLoop> stalled;
  for (const auto& instance : instances) {
    const auto it = heard_.find(instance);
    if (it == heard_.end() || !it->second.looping) {
      continue;
    }
    const Heard& heard = it->second;
    // The stall is seen through a status that still arrives: one after the
    // last growth of the count, within the timeout.
    if (heard.at - heard.advanced_at >= timeout &&
        (!stalled || heard.advanced_at < stalled->advanced_at)) {
      stalled = StalledLoop{instance, heard.iterations, heard.advanced_at};
    }
  }
  return stalled;
}

void Heartbeats::forget(const std::vector<std::string>& instances) {
  std::lock_guard lock(mutex_);
  for (const auto& instance : instances) {
    heard_.erase(instance);
  }
}

}  // namespace wbi::launch
