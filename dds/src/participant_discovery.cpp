// What a participant learns from discovery: the other participants (host, pid,
// start), who writes and reads which topic, and whether a writer's process ended.
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <mutex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include "participant_impl.hpp"

namespace wbi::dds::detail {

namespace {
Guid guid_of(const eprosima::fastrtps::rtps::GUID_t& rtps) {
  Guid guid{};
  std::copy(std::begin(rtps.guidPrefix.value), std::end(rtps.guidPrefix.value), guid.begin());
  std::copy(std::begin(rtps.entityId.value), std::end(rtps.entityId.value), guid.begin() + 12);
  return guid;
}

std::string guid_text(const eprosima::fastrtps::rtps::GUID_t& guid) {
  std::ostringstream out;
  out << guid;
  return out.str();
}
}  // namespace

void ParticipantImpl::on_participant_discovery(
    fdds::DomainParticipant* /*participant*/,
    eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& discovered) {
  using Status = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo::DISCOVERY_STATUS;
  const std::string prefix = prefix_text(discovered.info.m_guid.guidPrefix);
  std::lock_guard lock(discovery_mutex_);
  if (trace_handshakes_) {
    std::fprintf(stderr, "[dds %s] discovery of %s ('%s'): status %d\n", name.c_str(),
                 prefix.c_str(), discovered.info.m_participantName.c_str(),
                 static_cast<int>(discovered.status));
  }
  if (discovered.status == Status::REMOVED_PARTICIPANT ||
      discovered.status == Status::DROPPED_PARTICIPANT) {
    remote_participants_.erase(prefix);
    handshakes_.erase(prefix);
    return;
  }
  if (secured_) {
    handshakes_.try_emplace(prefix, Handshake{std::chrono::steady_clock::now(), false});
  }
  ParticipantInfo remote;
  remote.guid_prefix = prefix;
  remote.name = discovered.info.m_participantName.to_string();
  for (const auto& property : discovered.info.m_properties) {
    const std::string key = property.first();
    const std::string value = property.second();
    if (key == kHostProperty) {
      remote.host = value;
    } else if (key == kPidProperty) {
      remote.pid = std::strtol(value.c_str(), nullptr, 10);
    } else if (key == kStartProperty) {
      remote.start_ns = std::strtoll(value.c_str(), nullptr, 10);
    }
  }
  remote_participants_[prefix] = std::move(remote);
}

void ParticipantImpl::onParticipantAuthentication(
    fdds::DomainParticipant* /*participant*/,
    eprosima::fastrtps::rtps::ParticipantAuthenticationInfo&& info) {
  const std::string prefix = prefix_text(info.guid.guidPrefix);
  std::lock_guard lock(discovery_mutex_);
  if (trace_handshakes_) {
    std::fprintf(stderr, "[dds %s] handshake with %s: %s\n", name.c_str(), prefix.c_str(),
                 info.status == info.AUTHORIZED_PARTICIPANT ? "authorized" : "refused");
  }
  auto [at, added] =
      handshakes_.try_emplace(prefix, Handshake{std::chrono::steady_clock::now(), true});
  at->second.ended = true;
}

std::vector<PendingHandshake> ParticipantImpl::stalled_handshakes(
    std::chrono::nanoseconds at_least) const {
  std::vector<PendingHandshake> stalled;
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard lock(discovery_mutex_);
  for (const auto& [prefix, handshake] : handshakes_) {
    const auto waited = now - handshake.discovered_at;
    if (handshake.ended || waited < at_least) {
      continue;
    }
    PendingHandshake pending;
    const auto known = remote_participants_.find(prefix);
    if (known != remote_participants_.end()) {
      pending.remote = known->second;
    }
    pending.remote.guid_prefix = prefix;
    pending.waited_s = std::chrono::duration<double>(waited).count();
    stalled.push_back(std::move(pending));
  }
  return stalled;
}

bool ended_on_host(const ParticipantInfo& other, const std::string& host) {
  return !other.host.empty() && other.host == host && other.pid > 0 &&
         kill(static_cast<pid_t>(other.pid), 0) != 0 && errno == ESRCH;
}

std::optional<ParticipantInfo> ParticipantImpl::participant_of(const Guid& writer) const {
  std::string prefix = guid_hex(writer).substr(0, 24);
  if (prefix == self.guid_prefix) {
    return self;
  }
  std::lock_guard lock(discovery_mutex_);
  const auto known = remote_participants_.find(prefix);
  if (known == remote_participants_.end()) {
    return std::nullopt;
  }
  return known->second;
}

bool ParticipantImpl::writer_has_ended(const Guid& writer) const {
  // A participant no longer in discovery has left (a clean shutdown announces
  // it, possibly before its writers' unmatch reaches the readers).
  const auto owner = participant_of(writer);
  return !owner || ended_on_host(*owner, self.host);
}

std::string ParticipantImpl::describe_writer(const Guid& writer) const {
  const auto owner = participant_of(writer);
  std::string text = !owner                ? std::string("a participant not discovered")
                     : owner->name.empty() ? std::string("a participant")
                                           : "participant '" + owner->name + "'";
  if (owner && !owner->host.empty()) {
    text += " on host " + owner->host;
  }
  if (owner && owner->pid > 0) {
    text += ", pid " + std::to_string(owner->pid);
  }
  return text + " (writer " + guid_hex(writer) + ")";
}

Guid ParticipantImpl::oldest_writer_of(const std::string& topic) const {
  std::lock_guard lock(discovery_mutex_);
  Guid oldest{};
  std::int64_t oldest_start = 0;
  for (const auto& [key, endpoint] : remote_endpoints_) {
    const auto owner = remote_participants_.find(endpoint.participant);
    if (!endpoint.writer || endpoint.topic != topic || owner == remote_participants_.end() ||
        ended_on_host(owner->second, self.host)) {
      continue;
    }
    if (oldest == Guid{} || owner->second.start_ns < oldest_start) {
      oldest = endpoint.guid;
      oldest_start = owner->second.start_ns;
    }
  }
  return oldest;
}

std::vector<ParticipantInfo> ParticipantImpl::publishers_of(const std::string& topic) const {
  std::lock_guard lock(discovery_mutex_);
  std::vector<ParticipantInfo> publishers;
  for (const auto& [guid, endpoint] : remote_endpoints_) {
    if (!endpoint.writer || endpoint.topic != topic ||
        std::any_of(publishers.begin(), publishers.end(),
                    [&](const auto& p) { return p.guid_prefix == endpoint.participant; })) {
      continue;
    }
    const auto known = remote_participants_.find(endpoint.participant);
    ParticipantInfo publisher;
    if (known != remote_participants_.end()) {
      publisher = known->second;
    }
    publisher.guid_prefix = endpoint.participant;
    publishers.push_back(std::move(publisher));
  }
  return publishers;
}

void ParticipantImpl::on_publisher_discovery(fdds::DomainParticipant* /*participant*/,
                                             eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) {
  using Status = eprosima::fastrtps::rtps::WriterDiscoveryInfo::DISCOVERY_STATUS;
  const std::string key = guid_text(info.info.guid());
  {
    std::lock_guard lock(discovery_mutex_);
    if (info.status == Status::REMOVED_WRITER) {
      remote_endpoints_.erase(key);
    } else {
      const auto& qos = info.info.m_qos;
      remote_endpoints_[key] = {info.info.topicName().to_string(),
                                info.info.typeName().to_string(),
                                true,
                                qos.m_reliability.kind == fdds::RELIABLE_RELIABILITY_QOS,
                                qos.m_durability.kind == fdds::TRANSIENT_LOCAL_DURABILITY_QOS,
                                prefix_text(info.info.guid().guidPrefix),
                                guid_of(info.info.guid())};
    }
  }
  discovery_changed_.notify_all();
}

void ParticipantImpl::on_subscriber_discovery(
    fdds::DomainParticipant* /*participant*/,
    eprosima::fastrtps::rtps::ReaderDiscoveryInfo&& info) {
  using Status = eprosima::fastrtps::rtps::ReaderDiscoveryInfo::DISCOVERY_STATUS;
  const std::string key = guid_text(info.info.guid());
  {
    std::lock_guard lock(discovery_mutex_);
    if (info.status == Status::REMOVED_READER) {
      remote_endpoints_.erase(key);
    } else {
      remote_endpoints_[key] = {info.info.topicName().to_string(),
                                info.info.typeName().to_string(),
                                false,
                                false,
                                false,
                                prefix_text(info.info.guid().guidPrefix)};
    }
  }
  discovery_changed_.notify_all();
}

std::vector<TopicInfo> ParticipantImpl::collect_topics() const {
  std::map<std::string, TopicInfo> by_name;
  for (const auto& [guid, endpoint] : remote_endpoints_) {
    TopicInfo& topic = by_name[endpoint.topic];
    topic.name = endpoint.topic;
    topic.type = endpoint.type;
    if (endpoint.writer) {
      ++topic.writers;
      topic.writers_reliable = topic.writers_reliable && endpoint.reliable;
      topic.writers_transient_local = topic.writers_transient_local && endpoint.transient_local;
    } else {
      ++topic.readers;
    }
  }
  std::vector<TopicInfo> topics;
  for (auto& entry : by_name) {
    topics.push_back(std::move(entry.second));
  }
  return topics;
}

std::vector<TopicInfo> ParticipantImpl::discovered_topics() const {
  std::lock_guard lock(discovery_mutex_);
  return collect_topics();
}

bool ParticipantImpl::wait_for_topics(
    const std::function<bool(const std::vector<TopicInfo>&)>& holds,
    std::chrono::nanoseconds timeout) const {
  std::unique_lock lock(discovery_mutex_);
  return discovery_changed_.wait_for(lock, timeout, [&] { return holds(collect_topics()); });
}

}  // namespace wbi::dds::detail
