// One client's outgoing messages: bounded in bytes, so that a client that
// stops reading costs a fixed amount of memory and never blocks the DDS
// threads that fill it. When full, the oldest data messages go first (a
// viewer wants the newest sample); JSON messages (advertisements, replies,
// status) are never dropped. Drops are counted per channel for the client's
// status report. Thread-safe: DDS threads push, the socket's writer takes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "protocol.hpp"

namespace wbi::bridge {

using Payload = std::shared_ptr<const std::vector<std::uint8_t>>;

struct OutgoingMessage {
  // A text frame when `text` is set; else a binary frame of `header` (when
  // `channel_id` is set: a message-data frame) then `payload`.
  std::optional<std::string> text;
  protocol::MessageDataHeader header{};
  std::optional<std::uint32_t> channel_id;  // set: a data message, droppable
  Payload payload;                          // shared between the clients of a sample

  static OutgoingMessage json(std::string text);
  static OutgoingMessage data(std::uint32_t channel_id, const protocol::MessageDataHeader& header,
                              Payload payload);
  static OutgoingMessage binary(std::vector<std::uint8_t> bytes);  // not droppable

  std::size_t bytes() const;
};

class SendQueue {
 public:
  explicit SendQueue(std::size_t max_bytes) : max_bytes_(max_bytes) {}

  // Queues `message`, dropping the oldest data messages while the bound is
  // exceeded (a JSON message is queued even then). Returns true when the
  // writer was idle: the caller must then wake it (it takes until empty).
  bool push(OutgoingMessage message);
  // The next message for the writer; nullopt: empty, and the writer is idle
  // until the next push says to wake it.
  std::optional<OutgoingMessage> take();

  // Data messages dropped per channel since the last call (then reset).
  std::map<std::uint32_t, std::uint64_t> take_drops();
  std::uint64_t total_dropped() const;
  std::size_t queued_bytes() const;

 private:
  void drop_oldest_data_until_fits(std::size_t incoming);

  const std::size_t max_bytes_;
  mutable std::mutex mutex_;
  std::deque<OutgoingMessage> queue_;
  std::size_t bytes_ = 0;
  bool writer_busy_ = false;
  std::map<std::uint32_t, std::uint64_t> drops_;
  std::uint64_t total_dropped_ = 0;
};

}  // namespace wbi::bridge
