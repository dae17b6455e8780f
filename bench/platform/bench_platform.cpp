// wbi_bench_platform [--duration S] [--json FILE]
//
// How much of a latency budget the machine itself takes, before any DDS:
//
//   spin   one thread per core, pinned, reads the monotonic clock in a tight
//          loop; a gap between two reads is time the thread did not run
//          (interrupts, kernel threads, other processes, or the hypervisor
//          taking the virtual CPU). Counts of gaps > 50 us, > 200 us, > 1 ms.
//   timer  a thread sleeps to absolute 1 ms deadlines (clock_nanosleep,
//          TIMER_ABSTIME) and records how late it wakes: normal scheduling,
//          then SCHED_FIFO 80 where allowed. This is cyclictest's measure and
//          the best case of every 1 kHz loop in wbi.
//
// Spinning runs at normal priority, then at SCHED_FIFO 80 in 400 ms bursts
// (the kernel's real-time throttling would stop a FIFO spinner 50 ms of every
// second): gaps that remain under FIFO are not other processes' doing.
// Prints one JSON object (also to FILE with --json).
#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/percentile.hpp"

namespace {

std::int64_t monotonic_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1'000'000'000 + t.tv_nsec;
}

struct SpinResult {
  std::uint64_t over_50us = 0, over_200us = 0, over_1ms = 0;
  std::int64_t max_ns = 0;
  bool pinned = false;
};

void spin_for(std::int64_t duration_ns, SpinResult& r) {
  const std::int64_t end = monotonic_ns() + duration_ns;
  std::int64_t last = monotonic_ns();
  for (std::int64_t now = last; now < end; last = now) {
    now = monotonic_ns();
    const std::int64_t gap = now - last;
    r.over_50us += gap > 50'000 ? 1 : 0;
    r.over_200us += gap > 200'000 ? 1 : 0;
    r.over_1ms += gap > 1'000'000 ? 1 : 0;
    r.max_ns = std::max(r.max_ns, gap);
  }
}

// SCHED_FIFO at `priority` for the calling thread; false, with the reason in
// *refusal, where the OS refuses.
bool run_fifo(int priority, std::string* refusal) {
  sched_param param{};
  param.sched_priority = priority;
  if (const int error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param); error != 0) {
    *refusal = std::strerror(error);
    return false;
  }
  return true;
}

// fifo_priority 0: normal scheduling, spinning all along. Otherwise SCHED_FIFO,
// spinning 400 ms of every 500 (under the kernel's real-time throttling, 950
// of every 1000 ms), so that only interrupts, higher-priority kernel threads
// or the hypervisor can take the CPU away.
SpinResult spin_on(int cpu, double seconds, int fifo_priority, std::string* refusal) {
  SpinResult r;
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  r.pinned = pthread_setaffinity_np(pthread_self(), sizeof(set), &set) == 0;
  const auto total_ns = static_cast<std::int64_t>(seconds * 1e9);
  if (fifo_priority == 0) {
    spin_for(total_ns, r);
    return r;
  }
  if (!run_fifo(fifo_priority, refusal)) {
    return r;
  }
  for (std::int64_t spun = 0; spun < total_ns; spun += 400'000'000) {
    spin_for(400'000'000, r);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return r;
}

// Wake-up lateness of a 1 kHz loop on absolute deadlines; empty when the
// policy could not be set (the reason in *refusal).
std::vector<double> timer_lateness_us(double seconds, int fifo_priority, std::string* refusal) {
  std::vector<double> late_us;
  std::thread thread([&] {
    if (fifo_priority > 0 && !run_fifo(fifo_priority, refusal)) {
      return;
    }
    const auto ticks = static_cast<std::size_t>(seconds * 1000.0);
    late_us.reserve(ticks);
    timespec next{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    for (std::size_t k = 0; k < ticks; ++k) {
      next.tv_nsec += 1'000'000;
      if (next.tv_nsec >= 1'000'000'000) {
        next.tv_nsec -= 1'000'000'000;
        ++next.tv_sec;
      }
      clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
      const std::int64_t due =
          static_cast<std::int64_t>(next.tv_sec) * 1'000'000'000 + next.tv_nsec;
      late_us.push_back(1e-3 * static_cast<double>(monotonic_ns() - due));
    }
  });
  thread.join();
  return late_us;
}

nlohmann::json lateness_summary(const std::vector<double>& late_us, const std::string& refusal) {
  if (late_us.empty()) {
    return {{"refused", refusal}};
  }
  const auto over = [&](double limit) {
    return std::count_if(late_us.begin(), late_us.end(), [&](double v) { return v > limit; });
  };
  return {{"ticks", late_us.size()},
          {"p50_us", wbi::bench::percentile(late_us, 0.5)},
          {"p99_us", wbi::bench::percentile(late_us, 0.99)},
          {"max_us", *std::max_element(late_us.begin(), late_us.end())},
          {"over_200us", over(200.0)},
          {"over_1ms", over(1000.0)}};
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 10.0;
  std::string json_file;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--duration" && i + 1 < argc) {
      seconds = std::stod(argv[++i]);
    } else if (arg == "--json" && i + 1 < argc) {
      json_file = argv[++i];
    } else {
      std::cerr << "usage: wbi_bench_platform [--duration S (10)] [--json FILE]\n";
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  if (!(seconds > 0.0)) {
    std::cerr << "wbi_bench_platform: --duration must be > 0\n";
    return 2;
  }
  nlohmann::json out;
  out["duration_s"] = seconds;
  const int cpus = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (const auto& [key, priority] : {std::pair{"spin_normal", 0}, std::pair{"spin_fifo80", 80}}) {
    std::vector<SpinResult> spins(static_cast<std::size_t>(cpus));
    std::vector<std::string> refusals(static_cast<std::size_t>(cpus));
    std::vector<std::thread> spinners;
    for (int cpu = 0; cpu < cpus; ++cpu) {
      const auto i = static_cast<std::size_t>(cpu);
      spinners.emplace_back(
          [&, cpu, i, p = priority] { spins[i] = spin_on(cpu, seconds, p, &refusals[i]); });
    }
    for (auto& t : spinners) {
      t.join();
    }
    for (std::size_t i = 0; i < spins.size(); ++i) {
      const auto& r = spins[i];
      out[key].push_back({{"cpu", i},
                          {"pinned", r.pinned},
                          {"refused", refusals[i]},
                          {"gaps_over_50us", r.over_50us},
                          {"gaps_over_200us", r.over_200us},
                          {"gaps_over_1ms", r.over_1ms},
                          {"max_gap_us", 1e-3 * static_cast<double>(r.max_ns)}});
    }
  }
  std::string refusal;
  out["timer_1khz_normal"] = lateness_summary(timer_lateness_us(seconds, 0, &refusal), refusal);
  out["timer_1khz_fifo80"] = lateness_summary(timer_lateness_us(seconds, 80, &refusal), refusal);
  std::cout << out.dump(2) << std::endl;
  if (!json_file.empty()) {
    std::ofstream(json_file) << out.dump(2) << "\n";
  }
  return 0;
}
