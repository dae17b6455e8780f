// wbi_link_emulator: a wire between two TAP devices with a one-way delay,
// jitter and loss — a userspace `tc netem` for kernels without sch_netem.
//
//   wbi_link_emulator --tap-a NAME --tap-b NAME [--delay-ms D] [--jitter-ms J]
//                     [--loss-percent P] [--seed N] [--queue FRAMES]
//
// It creates both TAP devices, prints "ready" and forwards every Ethernet
// frame from one to the other through a DelayLine per direction (the same
// impairment both ways, drawn independently). The caller moves the devices
// into their network namespaces after "ready" (tests/multihost/netns_pair.sh).
// A frame written to a device that is down is lost (the link is cut). On
// SIGTERM or SIGINT it prints what it forwarded and dropped, and exits 0.
// It runs with SCHED_FIFO priority 50 when allowed (a warning otherwise).
#include <poll.h>
#include <sched.h>
#include <sys/prctl.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <string>

#include "delay_line.hpp"
#include "tap_device.hpp"

namespace {

using wbi::link_emulator::DelayLine;
using wbi::link_emulator::Impairment;
using wbi::link_emulator::TapDevice;

volatile std::sig_atomic_t stop_requested = 0;
void request_stop(int) { stop_requested = 1; }

std::int64_t monotonic_ns() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

struct Options {
  std::string tap_a;
  std::string tap_b;
  Impairment impairment;
  std::uint64_t seed = 1;
  std::size_t queue = 4096;
};

const char* const kUsage =
    "usage: wbi_link_emulator --tap-a NAME --tap-b NAME [--delay-ms D] [--jitter-ms J]\n"
    "                         [--loss-percent P] [--seed N] [--queue FRAMES]\n"
    "Forwards Ethernet frames between two new TAP devices with a one-way delay\n"
    "(uniform in D +- J ms, frames kept in order) and independent loss of P %.\n";

// The whole of `text` as a number, else an error naming the option.
double number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) {
    throw std::invalid_argument(option + ": expected a number, got '" + text + "'");
  }
  return value;
}

Options parse(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string option = argv[i];
    if (i + 1 >= argc) {
      throw std::invalid_argument(option + ": missing value");
    }
    const std::string value = argv[++i];
    if (option == "--tap-a") {
      options.tap_a = value;
    } else if (option == "--tap-b") {
      options.tap_b = value;
    } else if (option == "--delay-ms") {
      options.impairment.delay_ns = static_cast<std::int64_t>(number(option, value) * 1e6);
    } else if (option == "--jitter-ms") {
      options.impairment.jitter_ns = static_cast<std::int64_t>(number(option, value) * 1e6);
    } else if (option == "--loss-percent") {
      options.impairment.loss_probability = number(option, value) / 100.0;
    } else if (option == "--seed") {
      options.seed = static_cast<std::uint64_t>(number(option, value));
    } else if (option == "--queue") {
      options.queue = static_cast<std::size_t>(number(option, value));
    } else {
      throw std::invalid_argument("unknown option '" + option + "'");
    }
  }
  if (options.tap_a.empty() || options.tap_b.empty()) {
    throw std::invalid_argument("--tap-a and --tap-b are required");
  }
  return options;
}

// One direction: frames read from `from` wait in `line`, then are written to `to`.
struct Direction {
  const TapDevice& from;
  const TapDevice& to;
  DelayLine line;
  std::uint64_t undeliverable = 0;  // written while `to` was down (the link cut)

  void receive(std::span<std::uint8_t> buffer) {
    for (;;) {
      const ssize_t size = ::read(from.fd(), buffer.data(), buffer.size());
      if (size < 0) {
        if (errno == EAGAIN || errno == EINTR) {
          return;
        }
        throw std::runtime_error(from.name() + ": read failed: " + std::strerror(errno));
      }
      line.offer(buffer.first(static_cast<std::size_t>(size)), monotonic_ns());
    }
  }
  void send_due() {
    line.release(monotonic_ns(), [this](std::span<const std::uint8_t> frame) {
      if (::write(to.fd(), frame.data(), frame.size()) < 0) {
        ++undeliverable;
      }
    });
  }
  void report() const {
    const auto& c = line.counters();
    std::printf(
        "%s -> %s: forwarded %llu, lost %llu, queue full %llu, oversize %llu, "
        "undeliverable %llu\n",
        from.name().c_str(), to.name().c_str(), static_cast<unsigned long long>(c.forwarded),
        static_cast<unsigned long long>(c.lost), static_cast<unsigned long long>(c.overflow),
        static_cast<unsigned long long>(c.oversize),
        static_cast<unsigned long long>(undeliverable));
  }
};

int run(const Options& options) {
  // Signals arrive only while waiting in ppoll, so a stop never interrupts a write.
  sigset_t blocked;
  sigemptyset(&blocked);
  sigaddset(&blocked, SIGTERM);
  sigaddset(&blocked, SIGINT);
  sigprocmask(SIG_BLOCK, &blocked, nullptr);
  struct sigaction action {};
  action.sa_handler = request_stop;
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGINT, &action, nullptr);
  sigset_t while_waiting;
  sigemptyset(&while_waiting);
  // Wake-ups within 1 us of a frame's due time (the default slack is 50 us),
  // and ahead of ordinary processes: a wire's delay does not grow with the
  // machine's load (the processes at its ends may be late, the link is not).
  prctl(PR_SET_TIMERSLACK, 1000UL);
  sched_param priority{};
  priority.sched_priority = 50;
  if (sched_setscheduler(0, SCHED_FIFO, &priority) != 0) {
    std::fprintf(stderr, "wbi_link_emulator: no real-time priority (%s): delays grow with load\n",
                 std::strerror(errno));
  }

  const TapDevice a(options.tap_a);
  const TapDevice b(options.tap_b);
  Direction a_to_b{a, b, DelayLine(options.impairment, options.queue, options.seed)};
  Direction b_to_a{b, a, DelayLine(options.impairment, options.queue, options.seed + 1)};
  std::printf("ready: %s <-> %s\n", a.name().c_str(), b.name().c_str());
  std::fflush(stdout);

  static std::uint8_t buffer[65536];  // one frame at a time, larger than any MTU
  pollfd fds[2] = {{a.fd(), POLLIN, 0}, {b.fd(), POLLIN, 0}};
  while (stop_requested == 0) {
    a_to_b.send_due();
    b_to_a.send_due();
    std::int64_t next_ns = std::numeric_limits<std::int64_t>::max();
    for (const Direction* d : {&a_to_b, &b_to_a}) {
      if (d->line.next_due_ns() >= 0) {
        next_ns = std::min(next_ns, d->line.next_due_ns());
      }
    }
    timespec timeout{};
    const bool waits_for_a_frame = next_ns != std::numeric_limits<std::int64_t>::max();
    if (waits_for_a_frame) {
      const std::int64_t wait_ns = std::max<std::int64_t>(0, next_ns - monotonic_ns());
      timeout.tv_sec = wait_ns / 1'000'000'000;
      timeout.tv_nsec = wait_ns % 1'000'000'000;
    }
    if (ppoll(fds, 2, waits_for_a_frame ? &timeout : nullptr, &while_waiting) < 0) {
      if (errno == EINTR) {
        continue;
      }
      throw std::runtime_error(std::string("ppoll failed: ") + std::strerror(errno));
    }
    if ((fds[0].revents & POLLIN) != 0) {
      a_to_b.receive(buffer);
    }
    if ((fds[1].revents & POLLIN) != 0) {
      b_to_a.receive(buffer);
    }
  }
  a_to_b.report();
  b_to_a.report();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    }
  }
  try {
    return run(parse(argc, argv));
  } catch (const std::invalid_argument& error) {
    std::fprintf(stderr, "wbi_link_emulator: %s\n%s", error.what(), kUsage);
    return 2;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "wbi_link_emulator: %s\n", error.what());
    return 1;
  }
}
