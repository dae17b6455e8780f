// Subscribes to any topic whose type is a wbi message type, knowing only the
// topic name (the type comes from discovery), and hands over each sample as
// YAML text. Used by `wbi topic echo`; not for control loops.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "participant.hpp"

namespace wbi::dds {

class TopicEcho {
 public:
  using Callback = std::function<void(const std::string& yaml)>;

  // topic: as discovered (its type must be a wbi message type; throws
  // std::invalid_argument naming it otherwise). The reader's reliability and
  // durability follow the topic's writers, so that it matches every one of them.
  TopicEcho(Participant& participant, const TopicInfo& topic, Callback callback);
  ~TopicEcho();
  TopicEcho(const TopicEcho&) = delete;
  TopicEcho& operator=(const TopicEcho&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::dds
