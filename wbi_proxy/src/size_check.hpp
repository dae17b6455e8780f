// Argument size checks of the interface: the error names the argument, the
// expected and the given size.
#pragma once

#include <string>

#include "wbi/types.hpp"

namespace wbi::proxy {

inline void check_size(const char* what, Eigen::Index given, Eigen::Index expected) {
  if (given != expected) {
    throw Error(std::string(what) + " has size " + std::to_string(given) + ", expected " +
                std::to_string(expected));
  }
}

inline void check_index(const char* what, int index, int count) {
  if (index < 0 || index >= count) {
    throw Error(std::string(what) + " index " + std::to_string(index) + " out of range [0, " +
                std::to_string(count) + ")");
  }
}

}  // namespace wbi::proxy
