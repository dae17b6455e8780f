// Publisher<T>: writes samples of a wbi message type on one topic.
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

#include "detail/endpoints.hpp"
#include "message_traits.hpp"
#include "participant.hpp"

namespace wbi::dds {

template <Message T>
class Publisher {
 public:
  Publisher(Participant& participant, const std::string& topic, const std::string& qos_profile)
      : writer_(participant, topic, new typename MessageTraits<T>::TypeSupport(), qos_profile),
        max_size_(typename MessageTraits<T>::TypeSupport().is_bounded()
                      ? T::getMaxCdrSerializedSize()
                      : 0) {}

  // Returns false when the sample was not sent: larger than the largest
  // sample the IDL bounds allow (Fast DDS would send it anyway), or refused
  // by DDS (e.g. a reliable history full of unacknowledged samples). Sizes
  // of single sequences against the robot are checked by the components.
  bool publish(const T& sample) {
    if (max_size_ != 0 && T::getCdrSerializedSize(sample) > max_size_) {
      return false;
    }
    return writer_.write(&sample);
  }

  // Reliable profiles: waits until every matched reader acknowledged every
  // sample written so far. False on timeout.
  bool wait_acknowledged(std::chrono::nanoseconds timeout) {
    return writer_.wait_acknowledged(timeout);
  }

  // Remote and local readers currently matched.
  int matched() const { return writer_.matched(); }
  bool wait_for_subscribers(int count, std::chrono::nanoseconds timeout) const {
    return writer_.wait_matched(count, timeout);
  }
  // Until a reader in the participant of `peer` (the GUID of any of its
  // endpoints, e.g. the writer of a sample it sent) is matched: a command
  // written before that match would not reach that participant.
  bool wait_for_subscriber_of(const detail::Guid& peer, std::chrono::nanoseconds timeout) const {
    return writer_.wait_matched_participant(peer, timeout);
  }
  const std::string& topic() const { return writer_.topic(); }
  detail::Guid guid() const { return writer_.guid(); }

 private:
  detail::Writer writer_;
  // The largest size T's bounds allow, 0 when a sequence of T has no bound.
  // Computed once: the generated code walks every nested type for it.
  std::size_t max_size_;
};

}  // namespace wbi::dds
