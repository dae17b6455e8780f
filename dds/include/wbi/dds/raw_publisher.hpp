// Publishes already-serialized (CDR) samples of any wbi type, given by name,
// without deserializing them: for tools that replay recorded payloads.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "participant.hpp"

namespace wbi::dds {

class RawPublisher {
 public:
  // type_name: the DDS type name of the payloads, e.g. "wbi::msg::SensorSample"
  // (readers match on it). qos_profile: a profile of deploy/qos_profiles.xml.
  RawPublisher(Participant& participant, const std::string& topic, const std::string& type_name,
               const std::string& qos_profile);
  ~RawPublisher();
  RawPublisher(const RawPublisher&) = delete;
  RawPublisher& operator=(const RawPublisher&) = delete;

  // cdr: the payload as recorded, encapsulation header included. Copies into a
  // buffer that keeps its capacity, so a steady stream allocates nothing.
  // False when DDS refused the sample (e.g. a reliable history full).
  bool publish(std::span<const std::uint8_t> cdr);

  int matched() const;
  bool wait_for_subscribers(int count, std::chrono::nanoseconds timeout) const;
  // Reliable profiles: waits until every matched reader acknowledged every sample.
  bool wait_acknowledged(std::chrono::nanoseconds timeout);
  const std::string& topic() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::dds
