// A wbi message as the CDR bytes DDS carries (encapsulation header included,
// as `wbi record` stores them and raw endpoints pass them) and back, with its
// generated type support: for tools that read recordings or raw samples.
#pragma once

#include <cstdint>
#include <cstring>
#include <exception>
#include <span>
#include <vector>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "message_traits.hpp"

namespace wbi::dds {

// False when the bytes are not a T (Fast CDR throws on a sample cut short).
template <class T>
bool decode_cdr(std::span<const std::uint8_t> bytes, T& out) {
  typename MessageTraits<T>::TypeSupport type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(bytes.size()));
  std::memcpy(payload.data, bytes.data(), bytes.size());
  payload.length = static_cast<std::uint32_t>(bytes.size());
  try {
    return type.deserialize(&payload, &out);
  } catch (const std::exception&) {
    return false;
  }
}

// Empty when the message cannot be serialized (a sequence over its bound).
template <class T>
std::vector<std::uint8_t> encode_cdr(const T& message) {
  typename MessageTraits<T>::TypeSupport type;
  eprosima::fastrtps::rtps::SerializedPayload_t payload(
      type.getSerializedSizeProvider(const_cast<T*>(&message))());
  if (!type.serialize(const_cast<T*>(&message), &payload)) {
    return {};
  }
  return {payload.data, payload.data + payload.length};
}

}  // namespace wbi::dds
