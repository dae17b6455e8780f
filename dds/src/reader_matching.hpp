// Internal: reader settings that match every writer of a discovered topic.
#pragma once

#include "wbi/dds/detail/endpoints.hpp"
#include "wbi/dds/participant.hpp"

namespace wbi::dds::detail {

// Reliable only when every writer is (a reliable reader does not match a
// best-effort writer); transient local only when every writer keeps history.
inline ReaderOverrides matching_writers_of(const TopicInfo& topic) {
  ReaderOverrides overrides;
  overrides.set = true;
  overrides.reliable = topic.writers > 0 && topic.writers_reliable;
  overrides.transient_local = topic.writers > 0 && topic.writers_transient_local;
  return overrides;
}

}  // namespace wbi::dds::detail
