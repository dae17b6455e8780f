// An event's CDR bytes (wbi/events, as recorded or as a raw reader gets them)
// decoded with its generated type support. A raw reader and a typed reader of
// one type cannot share a participant (the type registered first serves
// both), so the recorders read events raw and decode them here.
#pragma once

#include <cstdint>
#include <span>

#include <wbi/msg/events.h>

namespace wbi::recording {

// False when the bytes do not decode (cut short, another type).
bool decode_event(std::span<const std::uint8_t> cdr, msg::Event& out);

}  // namespace wbi::recording
