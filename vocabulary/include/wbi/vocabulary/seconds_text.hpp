#pragma once
// A duration in messages, in as few digits as it needs: "30 s", "0.5 s",
// "0.102194 s" (six significant digits, as printf's %g), never "30.000000 s".
#include <cstdio>
#include <string>

namespace wbi {

inline std::string seconds_text(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", seconds);
  return text;
}

}  // namespace wbi
