// Internal: a Fast DDS type support that carries a sample's serialized bytes
// unchanged, under the name of the real type so that it matches its writers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <fastdds/dds/topic/TopicDataType.hpp>

namespace wbi::dds::detail {

struct RawBuffer {
  std::vector<std::uint8_t> bytes;  // capacity kept between samples
};

class RawType : public eprosima::fastdds::dds::TopicDataType {
 public:
  explicit RawType(const std::string& type_name);

  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override;
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override;
  std::function<uint32_t()> getSerializedSizeProvider(void* data) override;
  void* createData() override;
  void deleteData(void* data) override;
  bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle,
              bool force_md5) override;
};

}  // namespace wbi::dds::detail
