// Internal: the Fast DDS entities of a Participant, shared by the endpoints.
#pragma once

#include <condition_variable>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include "wbi/dds/detail/endpoints.hpp"
#include "wbi/dds/participant.hpp"

namespace wbi::dds::detail {

namespace fdds = eprosima::fastdds::dds;

// 24 lower-case hex digits.
inline std::string prefix_text(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text;
  for (const auto byte : prefix.value) {
    text += kDigits[byte >> 4];
    text += kDigits[byte & 0xf];
  }
  return text;
}

// Who this participant is, for others' discovery (ParticipantInfo): a robot
// refuses to start when its name is taken, and names the other by host and pid.
inline constexpr const char* kHostProperty = "wbi.host";
inline constexpr const char* kPidProperty = "wbi.pid";
inline constexpr const char* kStartProperty = "wbi.start_ns";

// Whether `other` is a participant of a process of `host` that has ended (its
// announcement stays until its lease ends).
bool ended_on_host(const ParticipantInfo& other, const std::string& host);

class ParticipantImpl : public fdds::DomainParticipantListener {
 public:
  explicit ParticipantImpl(const ParticipantOptions& options);
  ~ParticipantImpl() override;

  fdds::Publisher& publisher() { return *publisher_; }
  fdds::Subscriber& subscriber() { return *subscriber_; }

  // Registers the type if needed (takes ownership of type) and returns the
  // topic, shared by every endpoint of this participant on that name.
  fdds::Topic& acquire_topic(const std::string& name, fdds::TopicDataType* type);
  void release_topic(const std::string& name);

  fdds::DataWriterQos writer_qos(const std::string& profile) const;
  fdds::DataReaderQos reader_qos(const std::string& profile) const;

  std::vector<TopicInfo> discovered_topics() const;
  bool wait_for_topics(const std::function<bool(const std::vector<TopicInfo>&)>& holds,
                       std::chrono::nanoseconds timeout) const;

  std::vector<ParticipantInfo> publishers_of(const std::string& topic) const;

  // Whether the process of `writer`'s participant is known to have ended: it
  // left discovery, or it is of this host and its pid is gone. Allocates: once
  // per new writer.
  bool writer_has_ended(const Guid& writer) const;
  // "participant 'robot' on host h, pid 12 (writer <32 hex digits>)", as far
  // as discovery knows it, for log lines.
  std::string describe_writer(const Guid& writer) const;
  // The participant of `writer`: this one, a remote one discovery knows, or none.
  std::optional<ParticipantInfo> participant_of(const Guid& writer) const;
  // The remote writer of `topic` whose participant is the oldest of those
  // alive (the rule of a robot's name claim); all zero when none is known.
  Guid oldest_writer_of(const std::string& topic) const;

  std::vector<PendingHandshake> stalled_handshakes(std::chrono::nanoseconds at_least) const;

  int domain_id;
  std::string name;
  ParticipantInfo self;  // announced by participant_qos()

 private:
  void on_participant_discovery(fdds::DomainParticipant* participant,
                                eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override;
  void on_publisher_discovery(fdds::DomainParticipant* participant,
                              eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override;
  void on_subscriber_discovery(fdds::DomainParticipant* participant,
                               eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) override;
  void onParticipantAuthentication(
      fdds::DomainParticipant* participant,
      eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) override;

  std::vector<TopicInfo> collect_topics() const;  // caller holds discovery_mutex_

  struct SharedTopic {
    fdds::Topic* topic = nullptr;
    int users = 0;
  };
  // What discovery has told us about one remote endpoint.
  struct RemoteEndpoint {
    std::string topic;
    std::string type;
    bool writer = false;
    bool reliable = false;
    bool transient_local = false;
    std::string participant;  // its participant's GUID prefix (ParticipantInfo::guid_prefix)
    Guid guid{};
  };

  fdds::DomainParticipant* participant_ = nullptr;
  fdds::Publisher* publisher_ = nullptr;
  fdds::Subscriber* subscriber_ = nullptr;
  std::mutex topics_mutex_;
  std::map<std::string, SharedTopic> topics_;

  mutable std::mutex discovery_mutex_;
  mutable std::condition_variable discovery_changed_;
  std::map<std::string, RemoteEndpoint> remote_endpoints_;      // by GUID
  std::map<std::string, ParticipantInfo> remote_participants_;  // by GUID prefix

  // Secured participants: each remote participant's handshake, by GUID prefix.
  struct Handshake {
    std::chrono::steady_clock::time_point discovered_at{};
    bool ended = false;  // authenticated or refused
  };
  bool secured_ = false;
  bool trace_handshakes_ = false;  // WBI_DDS_TRACE_HANDSHAKES=1: one stderr line per step
  std::map<std::string, Handshake> handshakes_;
};

}  // namespace wbi::dds::detail
