#include "event_lines.hpp"

#include <ctime>

#include <nlohmann/json.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

#include "verb.hpp"

namespace wbi::cli {

namespace {

// A name off the wire: its vocabulary spelling, or "?" for a value outside it.
template <class WireEnum>
const char* wire_name(WireEnum value) {
  const auto known = msg::from_wire(value);
  return known ? to_string(*known) : "?";
}

template <class Enum>
std::string known_names() {
  std::string text;
  for (std::size_t i = 0; i < enum_count<Enum>(); ++i) {
    text += (i > 0 ? ", " : "") + std::string(to_string(static_cast<Enum>(i)));
  }
  return text;
}

}  // namespace

bool EventFilter::matches(const msg::Event& event) const {
  const auto severity = msg::from_wire(event.severity());
  const auto kind = msg::from_wire(event.kind());
  return (!robot || event.header().robot().to_string() == *robot) && severity &&
         *severity >= min_severity && kind && kinds.test(static_cast<std::size_t>(*kind));
}

std::bitset<enum_count<EventKind>()> parse_event_kinds(std::string_view list) {
  std::bitset<enum_count<EventKind>()> kinds;
  while (true) {
    const std::size_t comma = list.find(',');
    const std::string_view name = list.substr(0, comma);
    const auto kind = enum_from_name_any_case<EventKind>(name);
    if (!kind) {
      throw UsageError("unknown event kind '" + std::string(name) +
                       "' (kinds: " + known_names<EventKind>() + ")");
    }
    kinds.set(static_cast<std::size_t>(*kind));
    if (comma == std::string_view::npos) {
      return kinds;
    }
    list.remove_prefix(comma + 1);
  }
}

EventSeverity parse_event_severity(std::string_view name) {
  const auto severity = enum_from_name_any_case<EventSeverity>(name);
  if (!severity) {
    throw UsageError("unknown severity '" + std::string(name) +
                     "' (severities: " + known_names<EventSeverity>() + ")");
  }
  return *severity;
}

std::string clock_time(std::int64_t stamp_ns) {
  const std::time_t seconds = static_cast<std::time_t>(stamp_ns / 1'000'000'000);
  const auto millis = static_cast<int>((stamp_ns % 1'000'000'000) / 1'000'000);
  std::tm local{};
  localtime_r(&seconds, &local);
  char text[32];
  std::snprintf(text, sizeof text, "%02d:%02d:%02d.%03d", local.tm_hour, local.tm_min, local.tm_sec,
                millis);
  return text;
}

std::string human_line(const msg::Event& event) {
  std::string line = clock_time(event.header().stamp_ns());
  line.append(" ").append(wire_name(event.severity()));
  line.append(" ").append(event.participant().c_str()).append(":").append(event.source().c_str());
  line.append("  ").append(wire_name(event.kind()));
  if (event.header().robot().size() > 0) {
    line.append("  ").append(event.header().robot().c_str());
  }
  line.append("  ");
  if (event.subject().size() > 0) {
    line.append("[").append(event.subject().c_str()).append("] ");
  }
  line.append(event.text().c_str());
  if (event.suppressed() > 0) {
    line.append(" (+").append(std::to_string(event.suppressed())).append(" suppressed)");
  }
  return line;
}

std::string json_line(const msg::Event& event) {
  nlohmann::ordered_json out;
  out["stamp_ns"] = event.header().stamp_ns();
  out["time"] = clock_time(event.header().stamp_ns());
  out["seq"] = event.header().seq();
  out["robot"] = event.header().robot().to_string();
  out["participant"] = event.participant().to_string();
  out["source"] = event.source().to_string();
  out["severity"] = wire_name(event.severity());
  out["kind"] = wire_name(event.kind());
  out["subject"] = event.subject().to_string();
  out["text"] = event.text().to_string();
  out["suppressed"] = event.suppressed();
  return out.dump(-1, ' ', false, nlohmann::ordered_json::error_handler_t::replace);
}

}  // namespace wbi::cli
