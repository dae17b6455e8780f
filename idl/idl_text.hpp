// The IDL source of the wire contract, compiled into wbi::idl, so that a
// recording can carry the definition of every type it holds.
#pragma once

#include <string>

namespace wbi::msg {

// Self-contained OMG IDL text that defines `type_name` (e.g.
// "wbi::msg::SensorSample"): the text of common.idl and of the file that
// declares the type, without preprocessor lines. Throws std::invalid_argument
// naming the type when no wbi IDL file declares it.
std::string idl_text_for(const std::string& type_name);

}  // namespace wbi::msg
