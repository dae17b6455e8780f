// Receives the serialized (CDR) bytes of any topic, whatever its type, without
// deserializing them: for tools that count, measure or record samples.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>

#include "participant.hpp"
#include "producers.hpp"

namespace wbi::dds {

struct RawSample {
  std::span<const std::uint8_t> cdr;  // the payload as sent, encapsulation header included
  std::int64_t source_stamp_ns = 0;   // DDS source timestamp
  std::int64_t received_ns = 0;       // steady clock at arrival
};

class RawSubscriber {
 public:
  // Called on a DDS thread; the bytes are valid during the call only.
  using Callback = std::function<void(const RawSample& sample)>;

  // topic: as discovered. The reader's reliability and durability follow the
  // topic's writers, so that it matches every one of them.
  // producers: ProducerPolicy::one() takes one writer's samples (producers.hpp).
  RawSubscriber(Participant& participant, const TopicInfo& topic, Callback callback,
                ProducerPolicy producers = {});
  ~RawSubscriber();
  RawSubscriber(const RawSubscriber&) = delete;
  RawSubscriber& operator=(const RawSubscriber&) = delete;

  ProducerCounts producers() const;
  // Samples of the topic that never reached this reader and never will: it
  // fell behind and the writer's history no longer held them.
  std::int64_t samples_lost() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::dds
