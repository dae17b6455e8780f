// Puts what a component's one-producer readers drop (dds/producers.hpp) into
// its status: counters "foreign_samples" and "foreign_writers", and the line
// naming each foreign writer, or a rebind, as its last error.
//
//   on_configure:  auto events = runtime::count_producer_events(report());
//                  dds::Subscriber<T> s(p, topic, profile, cb, dds::ProducerPolicy::one(events));
#pragma once

#include <functional>

#include <wbi/dds/producers.hpp>

#include "status_report.hpp"

namespace wbi::runtime {

// Registers the two counters (allocates: call in on_configure). The function
// returned never allocates; `report` must outlive the readers that call it.
std::function<void(const dds::ProducerEvent&)> count_producer_events(StatusReport& report);

}  // namespace wbi::runtime
