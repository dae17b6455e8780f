// wbi_test_emit_event KIND SOURCE: publishes one event of KIND (a
// wbi::EventKind name, any case) about SOURCE on wbi/events, the way a
// component does (EventLog + EventPump), once a reader of wbi/events has
// matched (10 s at most; exit 1 without one), and waits until the matched
// readers acknowledged it (5 s at most; exit 1 otherwise).
// A trigger for windowed recorders in scripts (tests, benchmarks).
#include <chrono>
#include <iostream>
#include <string>
#include <thread>

#include <wbi/msg/events.h>
#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/event_pump.hpp>
#include <wbi/vocabulary/event.hpp>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: wbi_test_emit_event KIND SOURCE\n";
    return 2;
  }
  const auto kind = wbi::enum_from_name_any_case<wbi::EventKind>(argv[1]);
  if (!kind) {
    std::cerr << "wbi_test_emit_event: unknown event kind '" << argv[1] << "'\n";
    return 2;
  }
  wbi::dds::Participant participant("emit_event");
  wbi::runtime::EventLog log;
  wbi::runtime::EventPump pump(participant, log, argv[2]);
  // The pump's writer matches a reader about when a writer of our own does.
  wbi::dds::Publisher<wbi::msg::Event> probe(participant, wbi::dds::topics::kEvents,
                                             wbi::dds::qos::kEvents);
  if (!probe.wait_for_subscribers(1, std::chrono::seconds(10))) {
    std::cerr << "wbi_test_emit_event: no reader of wbi/events within 10 s\n";
    return 1;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  log.emit(wbi::EventSeverity::warning, *kind, "emitted by wbi_test_emit_event");
  if (!pump.flush_acknowledged(std::chrono::seconds(5))) {
    std::cerr << "wbi_test_emit_event: the event was not acknowledged within 5 s\n";
    return 1;
  }
  return 0;
}
