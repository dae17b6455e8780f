// wbi::dds::Participant: creating the Fast DDS participant (QoS profiles, its
// identity, transports, security), its shared topics, and the public API.
#include "wbi/dds/participant.hpp"

#include "wbi/dds/domain_id.hpp"
#include "wbi/dds/join_options.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>
#include <stdexcept>

#include <unistd.h>

#include <fastdds/rtps/transport/UDPTransportDescriptor.h>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "discovery.hpp"
#include "participant_impl.hpp"
#include "qos_layers.hpp"
#include "qos_profiles_default.hpp"
#include "security.hpp"
#include "transports.hpp"

namespace wbi::dds {

namespace fdds = eprosima::fastdds::dds;

int domain_id_from_environment() {
  const char* text = std::getenv("WBI_DOMAIN_ID");
  if (text == nullptr || *text == '\0') {
    return 0;
  }
  return domain_id_named(text, "WBI_DOMAIN_ID");
}

namespace {

// Loads each QoS profile source once per process (Fast DDS keeps profiles globally).
void load_qos_profiles(const std::string& requested_file) {
  static std::mutex mutex;
  static std::set<std::string> loaded;
  std::string file = requested_file;
  if (file.empty()) {
    if (const char* env = std::getenv("WBI_QOS_FILE"); env != nullptr && *env != '\0') {
      file = env;
    }
  }
  std::lock_guard lock(mutex);
  const std::string key = file.empty() ? std::string("<built-in>") : file;
  if (loaded.count(key) != 0) {
    return;
  }
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  std::string builtin(kDefaultQosProfiles);
  if (!file.empty()) {
    // The file's profiles first; the built-in ones it does not name fill in (qos_layers.hpp).
    std::ifstream in(file);
    if (!in) {
      throw std::runtime_error("cannot read the DDS QoS profiles file " + file);
    }
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (factory->load_XML_profiles_file(file) != ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("cannot load DDS QoS profiles from " + file +
                               " (not a Fast DDS profiles XML file?)");
    }
    builtin = detail::qos_profiles_without(builtin, detail::qos_profile_names(text));
  }
  if (!detail::qos_profile_names(builtin).empty() &&  // Fast DDS refuses an empty <profiles>
      factory->load_XML_profiles_string(builtin.data(), builtin.size()) !=
          ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error("cannot load the built-in DDS QoS profiles");
  }
  loaded.insert(key);
}

// Who this participant is, for others' discovery (ParticipantInfo; the names of
// its properties are in participant_impl.hpp).
ParticipantInfo own_info(const std::string& name) {
  ParticipantInfo info;
  info.name = name;
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) == 0) {
    info.host = host;
  }
  info.pid = static_cast<long>(getpid());
  info.start_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count();
  return info;
}

using detail::kHostProperty;
using detail::kPidProperty;
using detail::kStartProperty;

fdds::DomainParticipantQos participant_qos(const ParticipantOptions& options,
                                           const ParticipantInfo& info) {
  fdds::DomainParticipantQos qos = fdds::PARTICIPANT_QOS_DEFAULT;
  qos.name(options.name);
  auto& properties = qos.properties().properties();
  properties.emplace_back(kHostProperty, info.host, true);  // propagated: sent in discovery
  properties.emplace_back(kPidProperty, std::to_string(info.pid), true);
  properties.emplace_back(kStartProperty, std::to_string(info.start_ns), true);
  // A participant that starts announces itself at once, but learns of the
  // participants already running only from their periodic announcements: with
  // Fast DDS's default 3 s period a new client often waited ~3 s to connect to
  // a running service. 250 ms keeps discovery well under a second. A lease of
  // 5 s (default 20 s) forgets a killed process sooner.
  auto& discovery = qos.wire_protocol().builtin.discovery_config;
  discovery.leaseDuration_announcementperiod = eprosima::fastrtps::Duration_t(0, 250'000'000);
  discovery.leaseDuration = eprosima::fastrtps::Duration_t(5, 0);
  if (options.discovery == Discovery::localhost) {
    detail::use_loopback_transports(qos, options.domain_id,
                                    detail::local_transport_from_environment());
  } else {
    detail::use_network_transports(qos, options.discovery, options.network);
  }
  if (options.udp_receive_buffer_bytes > 0) {
    for (auto& transport : qos.transport().user_transports) {
      if (auto udp = std::dynamic_pointer_cast<eprosima::fastdds::rtps::UDPTransportDescriptor>(
              transport)) {
        udp->receiveBufferSize = static_cast<std::uint32_t>(options.udp_receive_buffer_bytes);
      }
    }
  }
  detail::use_security(qos, options.security);
  return qos;
}

}  // namespace

namespace detail {

ParticipantImpl::ParticipantImpl(const ParticipantOptions& options)
    : domain_id(options.domain_id), name(options.name), self(own_info(options.name)) {
  secured_ = options.security.enabled();
  const char* trace = std::getenv("WBI_DDS_TRACE_HANDSHAKES");
  trace_handshakes_ = secured_ && trace != nullptr && std::string(trace) == "1";
  if (domain_id < 0 || domain_id > kMaxDomainId) {
    throw std::invalid_argument("DDS domain id must be in " + domain_id_range() + ", got " +
                                std::to_string(domain_id));
  }
  load_qos_profiles(options.qos_file);
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  fdds::StatusMask mask = fdds::StatusMask::none();  // discovery callbacks only
  participant_ = factory->create_participant(domain_id, participant_qos(options, self), this, mask);
  if (participant_ == nullptr) {
    throw std::runtime_error("cannot create a DDS participant on domain " +
                             std::to_string(domain_id));
  }
  self.guid_prefix = prefix_text(participant_->guid().guidPrefix);
  publisher_ = participant_->create_publisher(fdds::PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(fdds::SUBSCRIBER_QOS_DEFAULT);
  if (publisher_ == nullptr || subscriber_ == nullptr) {
    throw std::runtime_error("cannot create a DDS publisher/subscriber on domain " +
                             std::to_string(domain_id));
  }
}

ParticipantImpl::~ParticipantImpl() {
  participant_->set_listener(nullptr);
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

fdds::Topic& ParticipantImpl::acquire_topic(const std::string& topic_name,
                                            fdds::TopicDataType* type) {
  // No TypeObject or TypeInformation in discovery data: every receiving
  // participant would build a dynamic type from it on its discovery thread,
  // racing with the generated message constructors, which re-register their
  // TypeObjects in the (not thread-safe) TypeObjectFactory: a crash seen with
  // several processes starting together. Tools that need a type by name
  // (TopicEcho) register the wbi types locally.
  type->auto_fill_type_object(false);
  type->auto_fill_type_information(false);
  fdds::TypeSupport support(type);  // owns type; freed here unless registered
  std::lock_guard lock(topics_mutex_);
  auto& shared = topics_[topic_name];
  if (shared.topic == nullptr) {
    const std::string type_name = support.get_type_name();
    if (participant_->find_type(type_name).empty() &&
        support.register_type(participant_) != ReturnCode_t::RETCODE_OK) {
      topics_.erase(topic_name);
      throw std::runtime_error("cannot register DDS type " + type_name);
    }
    shared.topic = participant_->create_topic(topic_name, type_name, fdds::TOPIC_QOS_DEFAULT);
    if (shared.topic == nullptr) {
      topics_.erase(topic_name);
      throw std::runtime_error("cannot create DDS topic '" + topic_name + "' of type " + type_name);
    }
  } else if (shared.topic->get_type_name() != support.get_type_name()) {
    throw std::invalid_argument("topic '" + topic_name + "' has type " +
                                shared.topic->get_type_name() + ", not " + support.get_type_name());
  }
  ++shared.users;
  return *shared.topic;
}

void ParticipantImpl::release_topic(const std::string& topic_name) {
  std::lock_guard lock(topics_mutex_);
  auto it = topics_.find(topic_name);
  if (it != topics_.end() && --it->second.users == 0) {
    participant_->delete_topic(it->second.topic);
    topics_.erase(it);
  }
}

fdds::DataWriterQos ParticipantImpl::writer_qos(const std::string& profile) const {
  fdds::DataWriterQos qos;
  if (publisher_->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw std::invalid_argument("unknown DDS QoS profile '" + profile + "' for a writer");
  }
  return qos;
}

fdds::DataReaderQos ParticipantImpl::reader_qos(const std::string& profile) const {
  fdds::DataReaderQos qos;
  if (subscriber_->get_datareader_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK) {
    throw std::invalid_argument("unknown DDS QoS profile '" + profile + "' for a reader");
  }
  return qos;
}

}  // namespace detail

Participant::Participant(const ParticipantOptions& options)
    : impl_(std::make_unique<detail::ParticipantImpl>(options)), options_(options) {}

Participant::Participant(const std::string& name)
    : Participant([&] {
        ParticipantOptions options;
        options.name = name;
        apply_environment(options);
        return options;
      }()) {}

Participant::~Participant() = default;

const ParticipantInfo& Participant::info() const { return impl_->self; }

std::vector<ParticipantInfo> Participant::publishers_of(const std::string& topic) const {
  return impl_->publishers_of(topic);
}

detail::Guid Participant::oldest_writer_of(const std::string& topic) const {
  return impl_->oldest_writer_of(topic);
}

bool Participant::participant_gone(const detail::Guid& guid) const {
  return impl_->writer_has_ended(guid);
}

std::string Participant::describe_writer(const detail::Guid& writer) const {
  return impl_->describe_writer(writer);
}

std::vector<PendingHandshake> Participant::stalled_handshakes(
    std::chrono::nanoseconds at_least) const {
  return impl_->stalled_handshakes(at_least);
}

bool Participant::has_ended(const ParticipantInfo& other) const {
  return detail::ended_on_host(other, impl_->self.host);
}

int Participant::domain_id() const { return impl_->domain_id; }
const std::string& Participant::name() const { return impl_->name; }

std::vector<TopicInfo> Participant::discovered_topics() const { return impl_->discovered_topics(); }

std::optional<TopicInfo> Participant::wait_for_topic(const std::string& topic,
                                                     std::chrono::nanoseconds timeout) const {
  std::optional<TopicInfo> found;
  impl_->wait_for_topics(
      [&](const std::vector<TopicInfo>& topics) {
        for (const auto& info : topics) {
          if (info.name == topic) {
            found = info;
            return true;
          }
        }
        return false;
      },
      timeout);
  return found;
}

bool Participant::wait_for_topics(const std::function<bool(const std::vector<TopicInfo>&)>& holds,
                                  std::chrono::nanoseconds timeout) const {
  return impl_->wait_for_topics(holds, timeout);
}

}  // namespace wbi::dds
