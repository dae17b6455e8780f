// EventLog::emit from a loop's thread, as a component calls it:
//   BM_EmitPublished   admitted events, an EventPump publishing them on
//                      wbi/events (WBI_DOMAIN_ID, default 229) from its own
//                      thread; one emit every 200 µs (the pump drains every
//                      5 ms: the queue of 128 never fills). Counters p50_ns,
//                      p99_ns, max_ns of single emits, published.
//   BM_EmitRateLimited one kind past its rate limit: the refused path.
// Target (issue 40): ≤ 5 µs per emit, and no emit ever waits for DDS.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <thread>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/event_pump.hpp>

#include "../common/percentile.hpp"

namespace {

using Clock = std::chrono::steady_clock;

int bench_domain() {
  const char* domain = std::getenv("WBI_DOMAIN_ID");
  return domain != nullptr ? std::atoi(domain) : 229;
}

void BM_EmitPublished(benchmark::State& state) {
  wbi::dds::ParticipantOptions options;
  options.domain_id = bench_domain();
  options.name = "bench_events";
  wbi::dds::Participant participant(options);
  wbi::runtime::EventLog log(wbi::runtime::EventRateLimit{.per_second = 1e6, .burst = 1e6});
  log.set_default_robot("bench");
  wbi::runtime::EventPump pump(participant, log, "bench_loop");
  std::vector<double> took_ns;
  took_ns.reserve(static_cast<std::size_t>(state.max_iterations));
  auto next = Clock::now();
  for (auto _ : state) {
    next += std::chrono::microseconds(200);
    state.PauseTiming();
    std::this_thread::sleep_until(next);
    state.ResumeTiming();
    const auto start = Clock::now();
    log.emit(wbi::EventSeverity::warning, wbi::EventKind::watchdog_trip,
             "watchdog: joint 'joint_3' got no command for 0.1 s: holding its position", "joint_3");
    took_ns.push_back(static_cast<double>((Clock::now() - start).count()));
  }
  pump.flush();
  state.counters["p50_ns"] = wbi::bench::percentile(took_ns, 0.5);
  state.counters["p99_ns"] = wbi::bench::percentile(took_ns, 0.99);
  state.counters["max_ns"] = wbi::bench::percentile(took_ns, 1.0);
  state.counters["published"] = static_cast<double>(pump.published());
  state.counters["overflowed"] = static_cast<double>(log.overflowed());
}
BENCHMARK(BM_EmitPublished)->Iterations(20000)->UseRealTime();

void BM_EmitRateLimited(benchmark::State& state) {
  wbi::runtime::EventLog log;  // 2 per second, burst 10: nearly all refused
  std::uint64_t refused = 0;
  for (auto _ : state) {
    refused += log.emit(wbi::EventSeverity::warning, wbi::EventKind::commands_rejected,
                        "command from 'x' rejected: 7 values for 8 joints")
                   ? 0
                   : 1;
  }
  state.counters["refused"] = static_cast<double>(refused);
}
BENCHMARK(BM_EmitRateLimited);

}  // namespace

BENCHMARK_MAIN();
