#include "channel_table.hpp"

#include <algorithm>
#include <cmath>

namespace wbi::bridge {

bool ChannelTable::add(protocol::Channel channel) {
  std::lock_guard lock(mutex_);
  const auto id = channel.id;
  return channels_.emplace(id, Entry{std::move(channel), false, {}}).second;
}

void ChannelTable::tell(const std::vector<std::pair<std::uint32_t, bool>>& changes) const {
  if (demand_) {
    for (const auto& [id, wanted] : changes) {
      demand_(id, wanted);
    }
  }
}

bool ChannelTable::set_advertised(std::uint32_t id, bool advertised) {
  std::vector<std::pair<std::uint32_t, bool>> changes;
  {
    std::lock_guard lock(mutex_);
    const auto found = channels_.find(id);
    if (found == channels_.end() || found->second.advertised == advertised) {
      return false;
    }
    found->second.advertised = advertised;
    if (!advertised && !found->second.subscribers.empty()) {
      found->second.subscribers.clear();  // the protocol's unadvertise ends them
      changes.emplace_back(id, false);
    }
  }
  tell(changes);
  return true;
}

std::vector<protocol::Channel> ChannelTable::advertised() const {
  std::lock_guard lock(mutex_);
  std::vector<protocol::Channel> out;
  for (const auto& [id, entry] : channels_) {
    if (entry.advertised) {
      out.push_back(entry.channel);
    }
  }
  return out;
}

std::optional<std::string> ChannelTable::topic_of(std::uint32_t id) const {
  std::lock_guard lock(mutex_);
  const auto found = channels_.find(id);
  return found == channels_.end() ? std::nullopt : std::optional(found->second.channel.topic);
}

std::optional<std::string> ChannelTable::subscribe(ClientId client,
                                                   const protocol::Subscription& subscription) {
  std::unique_lock lock(mutex_);
  for (const auto& [id, entry] : channels_) {
    for (const auto& subscriber : entry.subscribers) {
      if (subscriber.client == client && subscriber.subscription == subscription.id) {
        return "subscribe: subscription id " + std::to_string(subscription.id) +
               " is already in use (on " + entry.channel.topic + ")";
      }
    }
  }
  const auto found = channels_.find(subscription.channel_id);
  if (found == channels_.end() || !found->second.advertised) {
    return "subscribe: no channel " + std::to_string(subscription.channel_id) + " is advertised";
  }
  const std::uint64_t interval =
      subscription.max_rate_hz > 0.0
          ? static_cast<std::uint64_t>(std::llround(1e9 / subscription.max_rate_hz))
          : 0;
  found->second.subscribers.push_back({client, subscription.id, interval, 0});
  const bool first = found->second.subscribers.size() == 1;
  lock.unlock();
  if (first) {
    tell({{subscription.channel_id, true}});
  }
  return std::nullopt;
}

bool ChannelTable::unsubscribe(ClientId client, std::uint32_t subscription_id) {
  std::unique_lock lock(mutex_);
  for (auto& [id, entry] : channels_) {
    auto& list = entry.subscribers;
    const auto found = std::find_if(list.begin(), list.end(), [&](const Subscriber& s) {
      return s.client == client && s.subscription == subscription_id;
    });
    if (found != list.end()) {
      list.erase(found);
      const bool last = list.empty();
      const auto channel = id;
      lock.unlock();
      if (last) {
        tell({{channel, false}});
      }
      return true;
    }
  }
  return false;
}

void ChannelTable::forget(ClientId client) {
  std::vector<std::pair<std::uint32_t, bool>> changes;
  {
    std::lock_guard lock(mutex_);
    for (auto& [id, entry] : channels_) {
      if (std::erase_if(entry.subscribers,
                        [&](const Subscriber& s) { return s.client == client; }) > 0 &&
          entry.subscribers.empty()) {
        changes.emplace_back(id, false);
      }
    }
  }
  tell(changes);
}

bool ChannelTable::has_subscribers(std::uint32_t id) const {
  std::lock_guard lock(mutex_);
  const auto found = channels_.find(id);
  return found != channels_.end() && !found->second.subscribers.empty();
}

void ChannelTable::deliver(std::uint32_t id, std::uint64_t receive_ns,
                           std::span<const std::uint8_t> bytes) {
  std::lock_guard lock(mutex_);
  const auto found = channels_.find(id);
  if (found == channels_.end() || found->second.subscribers.empty() || server_ == nullptr) {
    return;
  }
  Payload payload;  // copied once, when a subscriber takes it
  for (auto& subscriber : found->second.subscribers) {
    if (subscriber.min_interval_ns != 0 && subscriber.last_sent_ns != 0 &&
        receive_ns - subscriber.last_sent_ns < subscriber.min_interval_ns) {
      continue;
    }
    subscriber.last_sent_ns = receive_ns;
    if (!payload) {
      payload = std::make_shared<const std::vector<std::uint8_t>>(bytes.begin(), bytes.end());
    }
    server_->send(
        subscriber.client,
        OutgoingMessage::data(
            id, protocol::message_data_header(subscriber.subscription, receive_ns), payload));
    forwarded_.fetch_add(1, std::memory_order_relaxed);
  }
}

}  // namespace wbi::bridge
