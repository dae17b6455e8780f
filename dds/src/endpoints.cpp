#include "wbi/dds/detail/endpoints.hpp"

#include <condition_variable>
#include <mutex>
#include <stdexcept>

#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "participant_impl.hpp"

namespace wbi::dds::detail {

std::int64_t steady_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
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

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  int matched_ = 0;
};

}  // namespace

struct WriterImpl : fdds::DataWriterListener {
  ParticipantImpl& participant;
  std::string topic_name;
  fdds::DataWriter* writer = nullptr;
  MatchCounter matches;

  WriterImpl(ParticipantImpl& p, std::string name) : participant(p), topic_name(std::move(name)) {}

  void on_publication_matched(fdds::DataWriter* /*writer*/,
                              const fdds::PublicationMatchedStatus& status) override {
    matches.set(status.current_count);
  }
};

Writer::Writer(Participant& participant, const std::string& topic, fdds::TopicDataType* type,
               const std::string& profile)
    : impl_(std::make_unique<WriterImpl>(participant.impl(), topic)) {
  const fdds::DataWriterQos qos = impl_->participant.writer_qos(profile);  // before taking the topic
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

int Writer::matched() const { return impl_->matches.get(); }

bool Writer::wait_matched(int count, std::chrono::nanoseconds timeout) const {
  return impl_->matches.wait_for(count, timeout);
}

const std::string& Writer::topic() const { return impl_->topic_name; }

struct ReaderImpl : fdds::DataReaderListener {
  ParticipantImpl& participant;
  std::string topic_name;
  ReaderSink& sink;
  fdds::DataReader* reader = nullptr;
  MatchCounter matches;

  ReaderImpl(ParticipantImpl& p, std::string name, ReaderSink& s)
      : participant(p), topic_name(std::move(name)), sink(s) {}

  void on_subscription_matched(fdds::DataReader* /*reader*/,
                               const fdds::SubscriptionMatchedStatus& status) override {
    matches.set(status.current_count);
  }

  void on_data_available(fdds::DataReader* data_reader) override {
    fdds::SampleInfo info;
    while (data_reader->take_next_sample(sink.storage(), &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) {
        continue;  // a dispose or unregister notice, not a sample
      }
      sink.on_sample({info.source_timestamp.to_ns(), steady_now_ns()});
    }
  }
};

Reader::Reader(Participant& participant, const std::string& topic, fdds::TopicDataType* type,
               const std::string& profile, ReaderSink& sink, ReaderOverrides overrides)
    : impl_(std::make_unique<ReaderImpl>(participant.impl(), topic, sink)) {
  fdds::DataReaderQos qos = impl_->participant.reader_qos(profile);
  if (overrides.set) {
    qos.reliability().kind =
        overrides.reliable ? fdds::RELIABLE_RELIABILITY_QOS : fdds::BEST_EFFORT_RELIABILITY_QOS;
    qos.durability().kind = overrides.transient_local ? fdds::TRANSIENT_LOCAL_DURABILITY_QOS
                                                      : fdds::VOLATILE_DURABILITY_QOS;
  }
  fdds::Topic& dds_topic = impl_->participant.acquire_topic(topic, type);
  const auto mask = fdds::StatusMask::subscription_matched() << fdds::StatusMask::data_available();
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

bool Reader::wait_matched(int count, std::chrono::nanoseconds timeout) const {
  return impl_->matches.wait_for(count, timeout);
}

const std::string& Reader::topic() const { return impl_->topic_name; }

}  // namespace wbi::dds::detail
