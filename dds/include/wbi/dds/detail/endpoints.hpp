// Untyped writer and reader behind Publisher<T> and Subscriber<T>: they own the
// Fast DDS entities; the typed templates own the samples.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "../producers.hpp"
#include "guid.hpp"

namespace eprosima::fastdds::dds {
class TopicDataType;
}

namespace wbi::dds {
class Participant;
}

namespace wbi::dds::detail {

struct WriterImpl;
struct ReaderImpl;

// Metadata of a received sample.
struct SampleInfo {
  std::int64_t source_stamp_ns = 0;  // DDS source timestamp set by the writer
  std::int64_t received_ns = 0;      // steady-clock time of arrival
  Guid writer{};                     // the writer that sent it: a restarted process has a new one
};

// 32 lower-case hex digits.
std::string guid_hex(const Guid& guid);
// Parses the 32 hex digits of guid_hex (either case); false when text is not that.
bool parse_guid_hex(const char* text, Guid& guid);

// Told when a remote endpoint matches or unmatches a local writer (on a DDS thread).
class MatchObserver {
 public:
  virtual ~MatchObserver() = default;
  virtual void on_match_changed(const Guid& remote, bool matched) = 0;
};

// Where a reader puts what it takes: the typed side owns the storage.
class ReaderSink {
 public:
  virtual ~ReaderSink() = default;
  virtual void* storage() = 0;                         // a T to deserialize into
  virtual void on_sample(const SampleInfo& info) = 0;  // storage() now holds a new sample
};

// Reader settings beyond the profile (used by tools that adapt to discovered writers).
struct ReaderOverrides {
  bool set = false;
  bool reliable = false;
  bool transient_local = false;
  // > 0: KEEP_LAST of this depth instead of the profile's (a recorder wants
  // every sample, also when its thread lags a burst behind).
  int history_depth = 0;
  // Samples arrive on a receive thread of this reader's own (its own port,
  // announced in discovery), not on the participant's shared one: a callback
  // on the shared thread may block until this reader has a sample (a reply).
  bool own_receive_thread = false;
};

class Writer {
 public:
  // Takes ownership of type. The observer, when given, must outlive the writer;
  // it hears every remote reader that matches or unmatches.
  Writer(Participant& participant, const std::string& topic,
         eprosima::fastdds::dds::TopicDataType* type, const std::string& profile,
         MatchObserver* observer = nullptr);
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  bool write(const void* sample);
  bool wait_acknowledged(std::chrono::nanoseconds timeout);
  int matched() const;
  bool wait_matched(int count, std::chrono::nanoseconds timeout) const;
  // Until a reader of the participant `peer` belongs to (any of its
  // endpoints' GUIDs: the prefix is the participant's) is matched.
  bool wait_matched_participant(const Guid& peer, std::chrono::nanoseconds timeout) const;
  const std::string& topic() const;
  Guid guid() const;

 private:
  std::unique_ptr<WriterImpl> impl_;
};

class Reader {
 public:
  // Takes ownership of type. The sink must outlive the reader; samples arrive on a DDS thread.
  Reader(Participant& participant, const std::string& topic,
         eprosima::fastdds::dds::TopicDataType* type, const std::string& profile, ReaderSink& sink,
         ReaderOverrides overrides = {}, ProducerPolicy producers = {});
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  int matched() const;
  bool wait_matched(int count, std::chrono::nanoseconds timeout) const;
  // Writers found on the topic whose QoS cannot serve this reader (said once on stderr).
  int incompatible_writers() const;
  // Samples of its writers that this reader never received and can no longer
  // get (gaps in their sequence numbers): a reader that fell behind a stream.
  std::int64_t samples_lost() const;
  // Bound to one producer (ProducerPolicy::one): which, and what it dropped.
  ProducerCounts producers() const;
  const std::string& topic() const;
  Guid guid() const;

 private:
  std::unique_ptr<ReaderImpl> impl_;
};

// Steady-clock now in ns, the time base of SampleInfo::received_ns.
std::int64_t steady_now_ns();

}  // namespace wbi::dds::detail
