#include "wbi/recording/recorded_events.hpp"

#include <algorithm>

#include <wbi/dds/topics.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "event_cdr.hpp"

namespace wbi::recording {

RecordedEvents read_events(const mcap::Reader& reader) {
  RecordedEvents out;
  bool has_channel = false;
  for (const auto& [id, channel] : reader.info().channels) {
    has_channel = has_channel || channel.topic == dds::topics::kEvents;
  }
  if (!has_channel) {
    return out;
  }
  msg::Event event;
  // File order, sorted after: no merge of chunks by time for a channel that is rare.
  auto cursor = reader.messages(mcap::Order::file);
  while (const auto* message = cursor.next()) {
    if (message->channel->topic != dds::topics::kEvents) {
      continue;
    }
    const bool decoded = decode_event(message->data, event);
    const auto severity = decoded ? msg::from_wire(event.severity()) : std::nullopt;
    const auto kind = decoded ? msg::from_wire(event.kind()) : std::nullopt;
    if (!severity || !kind) {
      ++out.undecoded;
      continue;
    }
    RecordedEvent& recorded = out.events.emplace_back();
    recorded.log_time = message->log_time;
    recorded.stamp_ns = event.header().stamp_ns();
    recorded.severity = *severity;
    recorded.kind = *kind;
    recorded.robot = event.header().robot().to_string();
    recorded.participant = event.participant().to_string();
    recorded.source = event.source().to_string();
    recorded.subject = event.subject().to_string();
    recorded.text = event.text().to_string();
    recorded.suppressed = event.suppressed();
  }
  std::stable_sort(
      out.events.begin(), out.events.end(),
      [](const RecordedEvent& a, const RecordedEvent& b) { return a.log_time < b.log_time; });
  return out;
}

}  // namespace wbi::recording
