// How every vocabulary enum is named: one table of spellings per enum, indexed
// by the enumerator's value, so that to_string, parsing and the check of a raw
// number (a value read off the wire) all come from the same place.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace wbi {

// Specialised once per vocabulary enum, next to it:
//   template <> struct EnumNames<E> { static constexpr std::array names{"A", "B"}; };
// the names in the order of the enumerators, which run 0, 1, … N−1.
template <class Enum>
struct EnumNames;

// The enum's spelling; "?" for a value outside it (only a cast can make one).
template <class Enum>
constexpr const char* enum_name(Enum value) {
  const auto index = static_cast<std::size_t>(value);
  return index < EnumNames<Enum>::names.size() ? EnumNames<Enum>::names[index] : "?";
}

// The enumerator spelt `name` (exactly, case included), if there is one.
template <class Enum>
constexpr std::optional<Enum> enum_from_name(std::string_view name) {
  for (std::size_t i = 0; i < EnumNames<Enum>::names.size(); ++i) {
    if (name == EnumNames<Enum>::names[i]) {
      return static_cast<Enum>(i);
    }
  }
  return std::nullopt;
}

// The same, with the case ignored: for command lines, where "rk4" names RK4.
template <class Enum>
constexpr std::optional<Enum> enum_from_name_any_case(std::string_view name) {
  const auto lower = [](char c) {
    return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
  };
  for (std::size_t i = 0; i < EnumNames<Enum>::names.size(); ++i) {
    const std::string_view candidate = EnumNames<Enum>::names[i];
    bool same = candidate.size() == name.size();
    for (std::size_t k = 0; same && k < name.size(); ++k) {
      same = lower(candidate[k]) == lower(name[k]);
    }
    if (same) {
      return static_cast<Enum>(i);
    }
  }
  return std::nullopt;
}

// The enumerator of a raw value (e.g. an IDL enum read off the wire, which may
// carry any 32-bit number), if it is one.
template <class Enum>
constexpr std::optional<Enum> enum_from_value(std::int64_t value) {
  if (value < 0 || static_cast<std::size_t>(value) >= EnumNames<Enum>::names.size()) {
    return std::nullopt;
  }
  return static_cast<Enum>(value);
}

// How many enumerators the enum has (its values are 0 … count − 1).
template <class Enum>
constexpr std::size_t enum_count() {
  return EnumNames<Enum>::names.size();
}

// "0 IDLE, 1 POSITION, … 5 PWM": every value and its name, for error messages.
template <class Enum>
std::string enum_values_text() {
  std::string text;
  for (std::size_t i = 0; i < EnumNames<Enum>::names.size(); ++i) {
    text += (i > 0 ? ", " : "") + std::to_string(i) + " " + EnumNames<Enum>::names[i];
  }
  return text;
}

}  // namespace wbi
