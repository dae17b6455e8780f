#include "raw_type.hpp"

#include <cstring>

namespace wbi::dds::detail {

RawType::RawType(const std::string& type_name) {
  setName(type_name.c_str());
  m_typeSize = 4096;  // initial payload size; payloads grow as needed (types may be unbounded)
  m_isGetKeyDefined = false;
}

bool RawType::serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) {
  const auto& buffer = *static_cast<RawBuffer*>(data);
  if (payload->max_size < buffer.bytes.size()) {
    payload->reserve(static_cast<std::uint32_t>(buffer.bytes.size()));
  }
  std::memcpy(payload->data, buffer.bytes.data(), buffer.bytes.size());
  payload->length = static_cast<std::uint32_t>(buffer.bytes.size());
  payload->encapsulation = buffer.bytes.size() > 1 && buffer.bytes[1] == 1 ? CDR_LE : CDR_BE;
  return true;
}

bool RawType::deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) {
  auto& buffer = *static_cast<RawBuffer*>(data);
  buffer.bytes.assign(payload->data, payload->data + payload->length);
  return true;
}

std::function<uint32_t()> RawType::getSerializedSizeProvider(void* data) {
  return [data] { return static_cast<uint32_t>(static_cast<RawBuffer*>(data)->bytes.size()); };
}

void* RawType::createData() { return new RawBuffer(); }

void RawType::deleteData(void* data) { delete static_cast<RawBuffer*>(data); }

bool RawType::getKey(void* /*data*/, eprosima::fastrtps::rtps::InstanceHandle_t* /*handle*/,
                     bool /*force_md5*/) {
  return false;  // wbi types have no key
}

}  // namespace wbi::dds::detail
