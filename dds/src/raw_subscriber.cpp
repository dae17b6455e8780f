#include "wbi/dds/raw_subscriber.hpp"

#include "raw_type.hpp"
#include "reader_matching.hpp"
#include "wbi/dds/detail/endpoints.hpp"

namespace wbi::dds {

namespace {
constexpr int kToolHistoryDepth = 256;  // samples a lagging tool thread may fall behind
}  // namespace

struct RawSubscriber::Impl : detail::ReaderSink {
  detail::RawBuffer buffer;
  Callback callback;
  std::unique_ptr<detail::Reader> reader;

  explicit Impl(Callback cb) : callback(std::move(cb)) {}
  ~Impl() override { reader.reset(); }  // no sample may arrive once buffer is gone

  void* storage() override { return &buffer; }

  void on_sample(const detail::SampleInfo& info) override {
    callback({buffer.bytes, info.source_stamp_ns, info.received_ns});
  }
};

RawSubscriber::RawSubscriber(Participant& participant, const TopicInfo& topic, Callback callback,
                             ProducerPolicy producers)
    : impl_(std::make_unique<Impl>(std::move(callback))) {
  detail::ReaderOverrides overrides = detail::matching_writers_of(topic);
  // The tools behind raw subscribers (wbi record, wbi topic hz) count or keep
  // every sample: with the stream profile's depth 1, a sample that arrives
  // while the tool's DDS thread is late replaces the one not yet taken.
  overrides.history_depth = kToolHistoryDepth;
  impl_->reader =
      std::make_unique<detail::Reader>(participant, topic.name, new detail::RawType(topic.type),
                                       qos::kStream, *impl_, overrides, std::move(producers));
}

ProducerCounts RawSubscriber::producers() const { return impl_->reader->producers(); }

std::int64_t RawSubscriber::samples_lost() const { return impl_->reader->samples_lost(); }

RawSubscriber::~RawSubscriber() = default;

}  // namespace wbi::dds
