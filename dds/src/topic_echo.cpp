#include "wbi/dds/topic_echo.hpp"

#include <sstream>
#include <stdexcept>

#include <fastrtps/types/DynamicDataFactory.h>
#include <fastrtps/types/DynamicPubSubType.h>
#include <fastrtps/types/TypeObjectFactory.h>
#include <wbi/msg/all_types.hpp>

#include "dynamic_printer.hpp"
#include "reader_matching.hpp"
#include "wbi/dds/detail/endpoints.hpp"

namespace wbi::dds {

namespace types = eprosima::fastrtps::types;

namespace {

types::DynamicType_ptr dynamic_type_of(const std::string& type_name) {
  wbi::msg::register_all_types();
  auto* factory = types::TypeObjectFactory::get_instance();
  const types::TypeIdentifier* identifier = factory->get_type_identifier(type_name, true);
  const types::TypeObject* object = factory->get_type_object(type_name, true);
  if (identifier == nullptr || object == nullptr) {
    throw std::invalid_argument("type '" + type_name + "' is not a wbi message type");
  }
  auto type = factory->build_dynamic_type(type_name, identifier, object);
  if (!type) {
    throw std::runtime_error("cannot build a dynamic type for '" + type_name + "'");
  }
  return type;
}

}  // namespace

struct TopicEcho::Impl : detail::ReaderSink {
  types::DynamicType_ptr type;
  types::DynamicData* data = nullptr;
  Callback callback;
  std::unique_ptr<detail::Reader> reader;

  Impl(types::DynamicType_ptr t, Callback cb)
      : type(std::move(t)),
        data(types::DynamicDataFactory::get_instance()->create_data(type)),
        callback(std::move(cb)) {}

  ~Impl() override {
    reader.reset();  // no sample may arrive once data is gone
    types::DynamicDataFactory::get_instance()->delete_data(data);
  }

  void* storage() override { return data; }

  void on_sample(const detail::SampleInfo& /*info*/) override {
    std::ostringstream yaml;
    detail::print_yaml(yaml, *data, type);
    callback(yaml.str());
  }
};

TopicEcho::TopicEcho(Participant& participant, const TopicInfo& topic, Callback callback)
    : impl_(std::make_unique<Impl>(dynamic_type_of(topic.type), std::move(callback))) {
  impl_->reader = std::make_unique<detail::Reader>(
      participant, topic.name, new types::DynamicPubSubType(impl_->type), qos::kStream, *impl_,
      detail::matching_writers_of(topic));
}

TopicEcho::~TopicEcho() = default;

}  // namespace wbi::dds
