// Linked into every wbi_add_test: a test process that dies of a signal
// (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) prints its stack to stderr first,
// so that a crash seen once under ctest -j4 or in CI leaves more in the log
// than "***Exception: SegFault". Frames of a PIE read "program(+0xOFFSET)":
// `addr2line -f -C -e build/tests/PROGRAM 0xOFFSET` names the function (and the
// line, in a build with debug information).
// Sanitizer builds keep their own, better reports.
#include <execinfo.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <utility>

namespace {

#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

void write_text(const char* text) {
  const ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  static_cast<void>(ignored);
}

constexpr std::pair<int, const char*> kSignals[] = {{SIGSEGV, "SIGSEGV"},
                                                    {SIGBUS, "SIGBUS"},
                                                    {SIGFPE, "SIGFPE"},
                                                    {SIGILL, "SIGILL"},
                                                    {SIGABRT, "SIGABRT"}};

// Only async-signal-safe calls, except backtrace(), which the constructor below
// has already called once so that it loads libgcc before any crash.
void print_stack_and_die(int signal_number) {
  write_text("\n*** the test process got ");
  for (const auto& [number, name] : kSignals) {
    if (number == signal_number) {
      write_text(name);
    }
  }
  write_text("; its stack (tests/support/crash_backtrace.cpp says how to read it):\n");
  void* frames[64];
  const int count = ::backtrace(frames, 64);
  ::backtrace_symbols_fd(frames, count, STDERR_FILENO);
  std::signal(signal_number, SIG_DFL);  // the default action: the same exit status
  std::raise(signal_number);
}

struct InstallCrashBacktrace {
  InstallCrashBacktrace() {
    void* frame[1];
    ::backtrace(frame, 1);
    for (const auto& [number, name] : kSignals) {
      std::signal(number, print_stack_and_die);
    }
  }
};
const InstallCrashBacktrace install_crash_backtrace;

#endif

}  // namespace
