#include "wbi/dds/raw_publisher.hpp"

#include "raw_type.hpp"
#include "wbi/dds/detail/endpoints.hpp"

namespace wbi::dds {

struct RawPublisher::Impl {
  detail::RawBuffer buffer;
  detail::Writer writer;

  Impl(Participant& participant, const std::string& topic, const std::string& type_name,
       const std::string& profile)
      : writer(participant, topic, new detail::RawType(type_name), profile) {}
};

RawPublisher::RawPublisher(Participant& participant, const std::string& topic,
                           const std::string& type_name, const std::string& qos_profile)
    : impl_(std::make_unique<Impl>(participant, topic, type_name, qos_profile)) {}

RawPublisher::~RawPublisher() = default;

bool RawPublisher::publish(std::span<const std::uint8_t> cdr) {
  impl_->buffer.bytes.assign(cdr.begin(), cdr.end());
  return impl_->writer.write(&impl_->buffer);
}

int RawPublisher::matched() const { return impl_->writer.matched(); }

bool RawPublisher::wait_for_subscribers(int count, std::chrono::nanoseconds timeout) const {
  return impl_->writer.wait_matched(count, timeout);
}

bool RawPublisher::wait_acknowledged(std::chrono::nanoseconds timeout) {
  return impl_->writer.wait_acknowledged(timeout);
}

const std::string& RawPublisher::topic() const { return impl_->writer.topic(); }

}  // namespace wbi::dds
