// The bridge's channels and who subscribes to them: the advertisements a
// client gets, and the fan-out of one sample to its subscribers (called on
// DDS threads: it copies the bytes once, shared by every client, and only
// queues; a client's socket is written on the server's thread).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "protocol.hpp"
#include "websocket_server.hpp"

namespace wbi::bridge {

class ChannelTable {
 public:
  // Told, outside the table's lock, when a channel gains its first subscriber
  // (true) or loses its last (false): the bridge reads a topic only while
  // someone watches it.
  using Demand = std::function<void(std::uint32_t channel, bool wanted)>;
  explicit ChannelTable(Demand demand) : demand_(std::move(demand)) {}

  // The server that carries deliveries (none before: nobody subscribed yet).
  void attach(WebSocketServer* server) {
    std::lock_guard lock(mutex_);
    server_ = server;
  }

  // Adds (not yet advertised) or returns false when the id is taken.
  bool add(protocol::Channel channel);
  // Whether the channel's advertisement changed; the caller tells the clients.
  bool set_advertised(std::uint32_t id, bool advertised);
  std::vector<protocol::Channel> advertised() const;
  std::optional<std::string> topic_of(std::uint32_t id) const;

  // A client's subscription; the error to send back when refused.
  std::optional<std::string> subscribe(ClientId client, const protocol::Subscription& subscription);
  bool unsubscribe(ClientId client, std::uint32_t subscription_id);
  void forget(ClientId client);  // every subscription of a gone client

  bool has_subscribers(std::uint32_t id) const;
  // Queues `bytes` to every subscriber of the channel whose rate allows it.
  void deliver(std::uint32_t id, std::uint64_t receive_ns, std::span<const std::uint8_t> bytes);

  std::uint64_t forwarded() const { return forwarded_.load(std::memory_order_relaxed); }

 private:
  struct Subscriber {
    ClientId client = 0;
    std::uint32_t subscription = 0;
    std::uint64_t min_interval_ns = 0;
    std::uint64_t last_sent_ns = 0;
  };
  struct Entry {
    protocol::Channel channel;
    bool advertised = false;
    std::vector<Subscriber> subscribers;
  };

  void tell(const std::vector<std::pair<std::uint32_t, bool>>& changes) const;

  const Demand demand_;
  WebSocketServer* server_ = nullptr;
  mutable std::mutex mutex_;
  std::map<std::uint32_t, Entry> channels_;
  std::atomic<std::uint64_t> forwarded_{0};
};

}  // namespace wbi::bridge
