// A plugin that needs a symbol no library of the process has (built against
// a library the program does not load): the loader cannot open it.
#include <wbi/plugin.hpp>

extern "C" int wbi_test_symbol_nobody_defines();

WBI_PLUGIN(/*catalog*/) {
  if (wbi_test_symbol_nobody_defines() != 0) {
    throw std::runtime_error("unreachable");
  }
}
