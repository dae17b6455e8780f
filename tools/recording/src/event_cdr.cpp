#include "event_cdr.hpp"

#include <cstring>
#include <exception>

#include <fastdds/rtps/common/SerializedPayload.h>
#include <wbi/msg/eventsPubSubTypes.h>

namespace wbi::recording {

bool decode_event(std::span<const std::uint8_t> cdr, msg::Event& out) {
  msg::EventPubSubType type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(cdr.size()));
  std::memcpy(payload.data, cdr.data(), cdr.size());
  payload.length = static_cast<std::uint32_t>(cdr.size());
  try {
    return type.deserialize(&payload, &out);
  } catch (const std::exception&) {
    return false;  // Fast CDR throws on a sample cut short
  }
}

}  // namespace wbi::recording
