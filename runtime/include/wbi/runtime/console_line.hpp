// Console lines that stay whole when several threads print. A hosted
// process's components, DDS listeners and main thread all print, and `wbi
// launch` reads stdout and stderr through one pipe, tagging each line with its
// process. `std::cout << a << b << std::endl` is one stdio call per piece, so
// another thread's line can land between them: the tag then sits on the wrong
// line and a tool that reads the log (the fault tests read the controller's
// progress lines) misses one. These write the text and its newline in a single
// call, flushed.
#pragma once

#include <cstdio>
#include <string_view>

namespace wbi::runtime {

// Writes `text` and a newline to `stream` (stdout or stderr) in one call and
// flushes it. `text` may hold several lines; they go out together.
void print_line(std::FILE* stream, std::string_view text);

}  // namespace wbi::runtime
