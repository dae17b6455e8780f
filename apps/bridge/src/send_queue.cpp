#include "send_queue.hpp"

#include <algorithm>
#include <utility>

namespace wbi::bridge {

namespace {
// A queued message's bookkeeping beside its bytes, so that many tiny
// messages also reach the bound.
constexpr std::size_t kOverhead = 64;
}  // namespace

OutgoingMessage OutgoingMessage::json(std::string text) {
  OutgoingMessage message;
  message.text = std::move(text);
  return message;
}

OutgoingMessage OutgoingMessage::data(std::uint32_t channel_id,
                                      const protocol::MessageDataHeader& header, Payload payload) {
  OutgoingMessage message;
  message.channel_id = channel_id;
  message.header = header;
  message.payload = std::move(payload);
  return message;
}

OutgoingMessage OutgoingMessage::binary(std::vector<std::uint8_t> bytes) {
  OutgoingMessage message;
  message.payload = std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes));
  return message;
}

std::size_t OutgoingMessage::bytes() const {
  return kOverhead + (text ? text->size() : 0) + (channel_id ? header.size() : 0) +
         (payload ? payload->size() : 0);
}

bool SendQueue::push(OutgoingMessage message) {
  std::lock_guard lock(mutex_);
  const std::size_t size = message.bytes();
  if (bytes_ + size > max_bytes_) {
    drop_oldest_data_until_fits(size);
    if (message.channel_id && bytes_ + size > max_bytes_) {
      ++drops_[*message.channel_id];  // only JSON is queued: the newest sample goes too
      ++total_dropped_;
      return false;
    }
  }
  bytes_ += size;
  queue_.push_back(std::move(message));
  if (writer_busy_) {
    return false;
  }
  writer_busy_ = true;
  return true;
}

std::optional<OutgoingMessage> SendQueue::take() {
  std::lock_guard lock(mutex_);
  if (queue_.empty()) {
    writer_busy_ = false;
    return std::nullopt;
  }
  OutgoingMessage message = std::move(queue_.front());
  queue_.pop_front();
  bytes_ -= message.bytes();
  return message;
}

void SendQueue::drop_oldest_data_until_fits(std::size_t incoming) {
  for (auto it = queue_.begin(); it != queue_.end() && bytes_ + incoming > max_bytes_;) {
    if (!it->channel_id) {
      ++it;
      continue;
    }
    ++drops_[*it->channel_id];
    ++total_dropped_;
    bytes_ -= it->bytes();
    it = queue_.erase(it);
  }
}

std::map<std::uint32_t, std::uint64_t> SendQueue::take_drops() {
  std::lock_guard lock(mutex_);
  return std::exchange(drops_, {});
}

std::uint64_t SendQueue::total_dropped() const {
  std::lock_guard lock(mutex_);
  return total_dropped_;
}

std::size_t SendQueue::queued_bytes() const {
  std::lock_guard lock(mutex_);
  return bytes_;
}

}  // namespace wbi::bridge
