#include "wbi/dds/detail/endpoints.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <fastdds/rtps/common/InstanceHandle.h>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "participant_impl.hpp"
#include "producer_binding.hpp"
#include "sequence_gaps.hpp"

namespace wbi::dds::detail {

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

namespace {

Guid to_guid(const eprosima::fastrtps::rtps::GUID_t& rtps) {
  Guid guid{};
  for (std::size_t i = 0; i < 12; ++i) {
    guid[i] = rtps.guidPrefix.value[i];
  }
  for (std::size_t i = 0; i < 4; ++i) {
    guid[12 + i] = rtps.entityId.value[i];
  }
  return guid;
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') {
    return c - '0';
  }
  if (c >= 'a' && c <= 'f') {
    return c - 'a' + 10;
  }
  if (c >= 'A' && c <= 'F') {
    return c - 'A' + 10;
  }
  return -1;
}

}  // namespace

std::string guid_hex(const Guid& guid) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string text(32, '0');
  for (std::size_t i = 0; i < guid.size(); ++i) {
    text[2 * i] = kDigits[guid[i] >> 4];
    text[2 * i + 1] = kDigits[guid[i] & 0xF];
  }
  return text;
}

bool parse_guid_hex(const char* text, Guid& guid) {
  if (text == nullptr) {
    return false;
  }
  for (std::size_t i = 0; i < guid.size(); ++i) {
    const int high = hex_value(text[2 * i]);
    const int low = high < 0 ? -1 : hex_value(text[2 * i + 1]);
    if (low < 0) {
      return false;
    }
    guid[i] = static_cast<std::uint8_t>(high * 16 + low);
  }
  return text[32] == '\0';
}

namespace {

// Counts matched remote endpoints and lets callers wait for a count.
class MatchCounter {
 public:
  void set(int current) {
    {
      std::lock_guard lock(mutex_);
      matched_ = current;
    }
    changed_.notify_all();
  }
  int get() const {
    std::lock_guard lock(mutex_);
    return matched_;
  }
  bool wait_for(int count, std::chrono::nanoseconds timeout) const {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return matched_ >= count; });
  }
  // Writers: which remote endpoints are matched, not only how many.
  void set_matched(const Guid& remote, bool matched) {
    {
      std::lock_guard lock(mutex_);
      std::erase(remotes_, remote);
      if (matched) {
        remotes_.push_back(remote);
      }
    }
    changed_.notify_all();
  }
  bool wait_for_participant(const Guid& peer, std::chrono::nanoseconds timeout) const {
    const auto same_participant = [&](const Guid& remote) {
      return std::equal(remote.begin(), remote.begin() + kGuidPrefixSize, peer.begin());
    };
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] {
      return std::any_of(remotes_.begin(), remotes_.end(), same_participant);
    });
  }

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  int matched_ = 0;
  std::vector<Guid> remotes_;  // writers only (set_matched)
};

}  // namespace

struct WriterImpl : fdds::DataWriterListener {
  ParticipantImpl& participant;
  std::string topic_name;
  fdds::DataWriter* writer = nullptr;
  MatchObserver* observer = nullptr;
  MatchCounter matches;

  WriterImpl(ParticipantImpl& p, std::string name, MatchObserver* o)
      : participant(p), topic_name(std::move(name)), observer(o) {}

  void on_publication_matched(fdds::DataWriter* /*writer*/,
                              const fdds::PublicationMatchedStatus& status) override {
    // Observer first: whoever waits on the count finds the observer up to date.
    if (status.current_count_change != 0) {
      const Guid reader =
          to_guid(eprosima::fastrtps::rtps::iHandle2GUID(status.last_subscription_handle));
      if (observer != nullptr) {
        observer->on_match_changed(reader, status.current_count_change > 0);
      }
      matches.set_matched(reader, status.current_count_change > 0);
    }
    matches.set(status.current_count);
  }
};

Writer::Writer(Participant& participant, const std::string& topic, fdds::TopicDataType* type,
               const std::string& profile, MatchObserver* observer)
    : impl_(std::make_unique<WriterImpl>(participant.impl(), topic, observer)) {
  const fdds::DataWriterQos qos =
      impl_->participant.writer_qos(profile);  // before taking the topic
  fdds::Topic& dds_topic = impl_->participant.acquire_topic(topic, type);
  impl_->writer = impl_->participant.publisher().create_datawriter(
      &dds_topic, qos, impl_.get(), fdds::StatusMask::publication_matched());
  if (impl_->writer == nullptr) {
    impl_->participant.release_topic(topic);
    throw std::runtime_error("cannot create a DDS writer on topic '" + topic + "'");
  }
}

Writer::~Writer() {
  impl_->writer->set_listener(nullptr);
  impl_->participant.publisher().delete_datawriter(impl_->writer);
  impl_->participant.release_topic(impl_->topic_name);
}

bool Writer::write(const void* sample) {
  return impl_->writer->write(const_cast<void*>(sample));  // Fast DDS 2.x takes void*, reads only
}

bool Writer::wait_acknowledged(std::chrono::nanoseconds timeout) {
  const auto seconds = std::chrono::duration<double>(timeout).count();
  return impl_->writer->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(seconds)) ==
         ReturnCode_t::RETCODE_OK;
}

int Writer::matched() const { return impl_->matches.get(); }

bool Writer::wait_matched(int count, std::chrono::nanoseconds timeout) const {
  return impl_->matches.wait_for(count, timeout);
}

bool Writer::wait_matched_participant(const Guid& peer, std::chrono::nanoseconds timeout) const {
  return impl_->matches.wait_for_participant(peer, timeout);
}

const std::string& Writer::topic() const { return impl_->topic_name; }

Guid Writer::guid() const { return to_guid(impl_->writer->guid()); }

struct ReaderImpl : fdds::DataReaderListener {
  ParticipantImpl& participant;
  std::string topic_name;
  ReaderSink& sink;
  fdds::DataReader* reader = nullptr;
  MatchCounter matches;
  std::unique_ptr<ProducerBinding> binding;  // ProducerPolicy::one_producer only
  std::function<void(const ProducerEvent&)> on_producer_event;
  std::function<Guid()> owner_of;

  ReaderImpl(ParticipantImpl& p, std::string name, ReaderSink& s, ProducerPolicy policy)
      : participant(p),
        topic_name(std::move(name)),
        sink(s),
        binding(policy.one_producer ? std::make_unique<ProducerBinding>() : nullptr),
        on_producer_event(std::move(policy.on_event)),
        owner_of(std::move(policy.owner)) {}

  void on_subscription_matched(fdds::DataReader* /*reader*/,
                               const fdds::SubscriptionMatchedStatus& status) override {
    if (binding && status.current_count_change < 0) {
      binding->on_unmatched(
          to_guid(eprosima::fastrtps::rtps::iHandle2GUID(status.last_publication_handle)));
    }
    matches.set(status.current_count);
  }

  // Whether a sample of `writer` goes to the sink (always, unless bound to one producer).
  bool admitted(const Guid& writer, std::int64_t received_ns) {
    if (!binding) {
      return true;
    }
    Guid previous{};
    Guid owner{};
    if (owner_of) {
      owner = owner_of();
    }
    const auto ended = [&](const Guid& bound) { return participant.writer_has_ended(bound); };
    switch (binding->admit(writer, received_ns, ended, previous, owner_of ? &owner : nullptr)) {
      case ProducerBinding::Verdict::take:
        return true;
      case ProducerBinding::Verdict::rebound:
        tell(ProducerEvent::Kind::rebound, writer,
             "wbi: '" + topic_name + "': now taking the samples of " +
                 participant.describe_writer(writer) + ", in place of writer " +
                 guid_hex(previous));
        return true;
      case ProducerBinding::Verdict::first_foreign:
        tell(ProducerEvent::Kind::foreign_sample, writer,
             "wbi: '" + topic_name + "': dropping the samples of a second writer, " +
                 participant.describe_writer(writer) + "; this reader takes those of " +
                 (previous != Guid{}
                      ? participant.describe_writer(previous)
                      : "the participant of its owner, " + participant.describe_writer(owner)) +
                 " only (one producer per stream)");
        return false;
      case ProducerBinding::Verdict::foreign:
        if (on_producer_event) {
          on_producer_event({ProducerEvent::Kind::foreign_sample, &writer, {}});
        }
        return false;
    }
    return false;
  }

  // Says a binding event on stderr (once per writer: not per sample) and to the owner.
  void tell(ProducerEvent::Kind kind, const Guid& writer, const std::string& text) {
    std::fprintf(stderr, "%s\n", text.c_str());
    if (on_producer_event) {
      on_producer_event({kind, &writer, text});
    }
  }

  // A writer on this topic that cannot serve this reader — typically a
  // best-effort stream of a real-time deploy (deploy/qos_realtime.xml) read by
  // a process started without that deploy's QoS file — would leave the reader
  // waiting in silence: say so, once per reader.
  void on_requested_incompatible_qos(fdds::DataReader* /*reader*/,
                                     const fdds::RequestedIncompatibleQosStatus& status) override {
    incompatible_writers.store(static_cast<int>(status.total_count));
    if (!incompatible_said.exchange(true)) {
      std::fprintf(stderr,
                   "wbi: a writer of '%s' does not match this reader: incompatible %s QoS (a "
                   "best-effort writer and a reliable reader? start this process with the "
                   "deploy file's qos_file, e.g. WBI_QOS_FILE=deploy/qos_realtime.xml)\n",
                   topic_name.c_str(), policy_name(status.last_policy_id));
    }
  }

  static const char* policy_name(fdds::QosPolicyId_t id) {
    switch (id) {
      case fdds::RELIABILITY_QOS_POLICY_ID:
        return "reliability";
      case fdds::DURABILITY_QOS_POLICY_ID:
        return "durability";
      case fdds::DEADLINE_QOS_POLICY_ID:
        return "deadline";
      case fdds::OWNERSHIP_QOS_POLICY_ID:
        return "ownership";
      default:
        return "some";
    }
  }

  std::atomic<int> incompatible_writers{0};
  std::atomic<bool> incompatible_said{false};
  // Samples this reader will never get: sent while it could not take them in
  // (a full socket buffer, a lossy link) and no longer in the writer's history
  // when it asked again (a stream's writer keeps only its newest sample).
  SequenceGaps gaps;

  void on_data_available(fdds::DataReader* data_reader) override {
    fdds::SampleInfo info;
    while (data_reader->take_next_sample(sink.storage(), &info) == ReturnCode_t::RETCODE_OK) {
      const auto& sequence = info.sample_identity.sequence_number();
      if (sequence != eprosima::fastrtps::rtps::SequenceNumber_t::unknown()) {
        gaps.observe(to_guid(info.sample_identity.writer_guid()), sequence.to64long());
      }
      if (!info.valid_data) {
        continue;  // a dispose or unregister notice, not a sample
      }
      const SampleInfo sample{info.source_timestamp.to_ns(), steady_now_ns(),
                              to_guid(info.sample_identity.writer_guid())};
      if (admitted(sample.writer, sample.received_ns)) {
        sink.on_sample(sample);
      }
    }
  }
};

Reader::Reader(Participant& participant, const std::string& topic, fdds::TopicDataType* type,
               const std::string& profile, ReaderSink& sink, ReaderOverrides overrides,
               ProducerPolicy producers)
    : impl_(std::make_unique<ReaderImpl>(participant.impl(), topic, sink, std::move(producers))) {
  fdds::DataReaderQos qos = impl_->participant.reader_qos(profile);
  if (overrides.set) {
    qos.reliability().kind =
        overrides.reliable ? fdds::RELIABLE_RELIABILITY_QOS : fdds::BEST_EFFORT_RELIABILITY_QOS;
    qos.durability().kind = overrides.transient_local ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS
                                                      : fdds::VOLATILE_DURABILITY_QOS;
  }
  if (overrides.history_depth > 0) {
    qos.history().kind = fdds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = overrides.history_depth;
  }
  if (overrides.own_receive_thread) {
    // Fast DDS (2.7+) gives such a reader unicast locators of its own, on a
    // port outside the participant's, and a receive thread per locator.
    qos.properties().properties().emplace_back("fastdds.unique_network_flows", "");
  }
  fdds::Topic& dds_topic = impl_->participant.acquire_topic(topic, type);
  const auto mask = fdds::StatusMask::subscription_matched()
                    << fdds::StatusMask::data_available()
                    << fdds::StatusMask::requested_incompatible_qos();
  impl_->reader =
      impl_->participant.subscriber().create_datareader(&dds_topic, qos, impl_.get(), mask);
  if (impl_->reader == nullptr) {
    impl_->participant.release_topic(topic);
    throw std::runtime_error("cannot create a DDS reader on topic '" + topic + "'");
  }
}

Reader::~Reader() {
  impl_->reader->set_listener(nullptr);
  impl_->participant.subscriber().delete_datareader(impl_->reader);
  impl_->participant.release_topic(impl_->topic_name);
}

int Reader::matched() const { return impl_->matches.get(); }

ProducerCounts Reader::producers() const {
  return impl_->binding ? impl_->binding->counts() : ProducerCounts{};
}

int Reader::incompatible_writers() const { return impl_->incompatible_writers.load(); }

std::int64_t Reader::samples_lost() const { return static_cast<std::int64_t>(impl_->gaps.lost()); }

bool Reader::wait_matched(int count, std::chrono::nanoseconds timeout) const {
  return impl_->matches.wait_for(count, timeout);
}

const std::string& Reader::topic() const { return impl_->topic_name; }

Guid Reader::guid() const { return to_guid(impl_->reader->guid()); }

}  // namespace wbi::dds::detail
