#include "wbi/runtime/producer_counters.hpp"

namespace wbi::runtime {

std::function<void(const dds::ProducerEvent&)> count_producer_events(StatusReport& report) {
  StatusCounter* samples = &report.counter("foreign_samples");
  StatusCounter* writers = &report.counter("foreign_writers");
  return [&report, samples, writers](const dds::ProducerEvent& event) {
    if (event.kind == dds::ProducerEvent::Kind::foreign_sample) {
      samples->add();
      if (!event.text.empty()) {  // the first sample of this writer
        writers->add();
      }
    }
    if (!event.text.empty()) {
      report.set_error(event.text);
    }
  };
}

}  // namespace wbi::runtime
