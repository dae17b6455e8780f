// The process's door to the DDS domain. Everything else in wbi reaches DDS
// through Participant and the typed endpoints (Publisher, Subscriber, Client,
// Server); nobody else touches Fast DDS entities.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "detail/guid.hpp"

#include "wbi/dds/network_options.hpp"

namespace wbi::dds {

namespace detail {
class ParticipantImpl;
}

// How participants find each other.
enum class Discovery {
  // Unicast discovery on 127.0.0.1 only (shared memory for data): nothing
  // leaves the machine. The default, and what every test uses.
  localhost,
  // Standard SPDP multicast on all interfaces, for robots spread over hosts.
  // This and the modes below use UDP only (no shared memory across hosts).
  multicast,
  // Unicast discovery to NetworkOptions::peers only, for networks without multicast.
  peers,
  // A Fast DDS discovery server at NetworkOptions::discovery_server.
  server,
};

// The names of the QoS profiles in deploy/qos_profiles.xml.
namespace qos {
inline constexpr const char* kStream = "wbi.stream";               // sensors, state, clock
inline constexpr const char* kCommand = "wbi.command";             // actuator commands, parameters
inline constexpr const char* kLatched = "wbi.latched";             // robot descriptions
inline constexpr const char* kRequestReply = "wbi.request_reply";  // services
inline constexpr const char* kStatus = "wbi.status";               // heartbeats
inline constexpr const char* kEvents = "wbi.events";               // wbi/events
}  // namespace qos

// WBI_DOMAIN_ID from the environment, 0 when unset. Throws std::invalid_argument
// when it is not an integer in [0, kMaxDomainId] (domain_id.hpp).
int domain_id_from_environment();

struct ParticipantOptions {
  int domain_id = domain_id_from_environment();
  std::string name = "wbi";
  Discovery discovery = Discovery::localhost;
  // QoS profile file; empty: WBI_QOS_FILE when set, else the profiles compiled in.
  std::string qos_file;
  // Peers, interface allow-list and discovery server for the non-localhost modes.
  NetworkOptions network;
  // DDS Security; off by default.
  SecurityOptions security;
  // Size asked for the UDP sockets' receive buffers; 0: the OS default
  // (net.core.rmem_default, 208 KiB on Debian 12). The kernel grants at most
  // net.core.rmem_max. A reader whose process stalls longer than its buffer
  // lasts loses the datagrams that overflow it: a recorder asks for more.
  int udp_receive_buffer_bytes = 0;
};

// A topic seen on the domain through discovery (remote endpoints only).
struct TopicInfo {
  std::string name;
  std::string type;
  int writers = 0;
  int readers = 0;
  bool writers_reliable = true;         // every known writer is reliable
  bool writers_transient_local = true;  // every known writer keeps history for late joiners
  bool operator==(const TopicInfo&) const = default;
};

// A participant as discovery announces it. wbi's participants announce their
// host name, process id and creation time (properties wbi.host, wbi.pid,
// wbi.start_ns); another vendor's or tool's participants leave them empty/0.
struct ParticipantInfo {
  std::string guid_prefix;  // 24 hex digits: the participant's part of every GUID
  std::string name;
  std::string host;
  long pid = 0;
  std::int64_t start_ns = 0;  // system clock at creation
};

// A remote participant that a secured participant discovered but whose DDS
// Security handshake has neither authenticated nor refused it since.
struct PendingHandshake {
  ParticipantInfo remote;
  double waited_s = 0.0;  // since its discovery
};

class Participant {
 public:
  explicit Participant(const ParticipantOptions& options = {});
  // Default options with this name, then the WBI_* environment (dds::apply_environment).
  explicit Participant(const std::string& name);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  int domain_id() const;
  const std::string& name() const;
  // The options it was made with: components that need a participant of their
  // own (the DDS proxy) copy them, so they reach the same peers with the same identity.
  const ParticipantOptions& options() const { return options_; }

  // Topics that remote participants publish or subscribe, sorted by name.
  std::vector<TopicInfo> discovered_topics() const;
  // Waits until a remote writer or reader of `topic` is known.
  std::optional<TopicInfo> wait_for_topic(const std::string& topic,
                                          std::chrono::nanoseconds timeout) const;
  // Waits until `holds` is true of the discovered topics (asked at once and at
  // each endpoint discovered or removed), at most `timeout`; returns whether it
  // held. `holds` runs under the discovery lock: it must not call back into
  // this participant.
  bool wait_for_topics(const std::function<bool(const std::vector<TopicInfo>&)>& holds,
                       std::chrono::nanoseconds timeout) const;

  // This participant, as others see it.
  const ParticipantInfo& info() const;
  // The remote participants that have a writer of `topic` (each once), as
  // discovery knows them now; a killed process's stay until their lease
  // (5 s) ends.
  std::vector<ParticipantInfo> publishers_of(const std::string& topic) const;
  // Whether `other` belongs to a process of this host that has ended (it
  // stays in discovery until its lease ends): a killed robot, before its respawn.
  bool has_ended(const ParticipantInfo& other) const;
  // The remote writer of `topic` whose participant is the oldest alive (the
  // robot that holds its name, for wbi/<robot>/description); all zero when
  // discovery knows none. Allocates: for start-up, not for a loop.
  detail::Guid oldest_writer_of(const std::string& topic) const;
  // Whether the participant of `guid` (any GUID of it: its prefix counts) is
  // gone: no longer in discovery, or a process of this host that has ended.
  // Allocates: for rare decisions (a joint claim), not for a loop.
  bool participant_gone(const detail::Guid& guid) const;
  // "participant 'pd' on host h, pid 12 (writer <32 hex digits>)", as far as
  // discovery knows it, for log lines.
  std::string describe_writer(const detail::Guid& writer) const;
  // Secured participants only (empty otherwise): the remote participants whose
  // handshake has been pending for at least `at_least`. Fast DDS 2.9's
  // handshake race (dds/README.md, "Secured start-up") leaves such a pair stuck
  // for good; a participant that left is forgotten at its lease's end (5 s).
  // Allocates: for start-up, not for a loop.
  std::vector<PendingHandshake> stalled_handshakes(std::chrono::nanoseconds at_least) const;

  detail::ParticipantImpl& impl() { return *impl_; }

 private:
  std::unique_ptr<detail::ParticipantImpl> impl_;
  ParticipantOptions options_;
};

}  // namespace wbi::dds
