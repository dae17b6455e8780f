// The source stamp of a recorded sample, read from its CDR bytes: MCAP's
// publish time. wbi messages that carry a Header have it as their first
// member, so Header.stamp_ns sits right after the robot name.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace wbi::recording {

// True when the type's IDL text (idl_text_for) declares `Header header;` as
// the first member of the struct named by type_name (e.g. "wbi::msg::SensorSample").
bool starts_with_header(const std::string& type_name, const std::string& idl_text);

// Header.stamp_ns of a payload whose type starts with a Header; nullopt when
// the bytes are too short or the encapsulation is not plain CDR (XCDR1 or 2).
std::optional<std::int64_t> header_stamp_ns(std::span<const std::uint8_t> cdr);
// Header.seq of such a payload (the stream's sequence number), likewise.
std::optional<std::uint64_t> header_seq(std::span<const std::uint8_t> cdr);

}  // namespace wbi::recording
