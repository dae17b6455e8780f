// What the verbs that read a recording (`bag info`, `play`) say about the file
// itself: not a recording at all (empty, no MCAP magic, nothing readable) is a
// one-line error; a truncated one is read as far as it goes and ends with one
// line saying where it ends and what was lost.
#pragma once

#include <cstdint>
#include <string>

#include <wbi/mcap/reader.hpp>

namespace wbi::cli {

// Throws std::runtime_error "FILE: what is wrong" when `info` has nothing readable.
void require_readable_recording(const std::string& file, const mcap::FileInfo& info);

// "FILE: <where it ends>; lost: …; readable: N messages in B bytes", for a truncated file.
std::string truncation_line(const std::string& file, const mcap::FileInfo& info);

// "2026-11-22 00:39:55.123456789 UTC"
std::string utc_time(std::uint64_t ns);

}  // namespace wbi::cli
