// The shape of a collision geometry fixed to a link: the one contact-shape enum
// of the robot config, both simulation engines and the MJCF writer.
#pragma once

#include <cstdint>

#include "wbi/vocabulary/enum_names.hpp"

namespace wbi {

enum class ContactShape : std::uint8_t {
  box,      // full extents `size` [m]
  sphere,   // `radius` [m]
  capsule,  // `radius` and `length` between its end spheres' centres, along z [m]
};

template <>
struct EnumNames<ContactShape> {
  static constexpr std::array names{"box", "sphere", "capsule"};
};

constexpr const char* to_string(ContactShape shape) { return enum_name(shape); }

}  // namespace wbi
