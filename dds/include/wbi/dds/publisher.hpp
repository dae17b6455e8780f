// Publisher<T>: writes samples of a wbi message type on one topic.
#pragma once

#include <chrono>
#include <string>

#include "detail/endpoints.hpp"
#include "message_traits.hpp"
#include "participant.hpp"

namespace wbi::dds {

template <Message T>
class Publisher {
 public:
  Publisher(Participant& participant, const std::string& topic, const std::string& qos_profile)
      : writer_(participant, topic, new typename MessageTraits<T>::TypeSupport(), qos_profile) {}

  // Returns false when DDS refused the sample (e.g. history full of unacknowledged samples).
  bool publish(const T& sample) { return writer_.write(&sample); }

  // Remote and local readers currently matched.
  int matched() const { return writer_.matched(); }
  bool wait_for_subscribers(int count, std::chrono::nanoseconds timeout) const {
    return writer_.wait_matched(count, timeout);
  }
  const std::string& topic() const { return writer_.topic(); }

 private:
  detail::Writer writer_;
};

}  // namespace wbi::dds
