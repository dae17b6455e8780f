#include "event_cdr.hpp"

#include <wbi/dds/cdr.hpp>

namespace wbi::recording {

bool decode_event(std::span<const std::uint8_t> cdr, msg::Event& out) {
  return dds::decode_cdr(cdr, out);
}

}  // namespace wbi::recording
