// The command-line words of a windowed recorder: its window and its trigger kinds.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string_view>

#include <wbi/recording/window_recorder.hpp>

namespace wbi::recording {

namespace {

// A number of seconds >= 0, the whole text; nullopt otherwise.
std::optional<double> parse_seconds(std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value) ||
      value < 0) {
    return std::nullopt;
  }
  return value;
}

std::chrono::nanoseconds to_ns(double seconds) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(std::llround(seconds * 1e9)));
}

}  // namespace

WindowSpan parse_window(const std::string& text) {
  const auto colon = text.find(':');
  // Beyond a day a window is not a window: it would be a recording.
  constexpr double kMaxSeconds = 86400;
  if (colon != std::string::npos) {
    const auto before = parse_seconds(std::string_view(text).substr(0, colon));
    const auto after = parse_seconds(std::string_view(text).substr(colon + 1));
    if (before && after && *before <= kMaxSeconds && *after <= kMaxSeconds &&
        *before + *after > 0) {
      return {to_ns(*before), to_ns(*after)};
    }
  }
  throw std::invalid_argument("--window '" + text +
                              "': not BEFORE:AFTER in seconds (each 0 to 86400, not both 0; "
                              "e.g. 5:2)");
}

std::vector<EventKind> parse_trigger_kinds(const std::string& text) {
  std::vector<EventKind> kinds;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const auto comma = std::min(text.find(',', begin), text.size());
    const std::string name = text.substr(begin, comma - begin);
    const auto kind = enum_from_name_any_case<EventKind>(name);
    if (!kind) {
      std::string known;
      for (const char* candidate : EnumNames<EventKind>::names) {
        known += (known.empty() ? "" : ", ") + std::string(candidate);
      }
      throw std::invalid_argument("--trigger: unknown event kind '" + name + "' (known: " + known +
                                  ")");
    }
    if (std::find(kinds.begin(), kinds.end(), *kind) == kinds.end()) {
      kinds.push_back(*kind);
    }
    begin = comma + 1;
  }
  return kinds;
}

}  // namespace wbi::recording
