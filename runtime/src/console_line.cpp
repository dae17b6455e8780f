#include "wbi/runtime/console_line.hpp"

namespace wbi::runtime {

void print_line(std::FILE* stream, std::string_view text) {
  // One formatted call: stdio writes it under the stream's lock, and for the
  // unbuffered stderr as one write(2), which a pipe keeps whole up to 4 KiB.
  std::fprintf(stream, "%.*s\n", static_cast<int>(text.size()), text.data());
  std::fflush(stream);
}

}  // namespace wbi::runtime
