// The windowed recorder's cost per sample (`wbi record --window`): what a DDS
// callback spends putting a sample into the ring, and what the writer thread
// spends copying a window back out.
//
//   BM_RingPush/<bytes>         a steady ring (full, evicting the oldest on
//                               every push) of 64 MiB; bytes: the CDR payload
//                               (832: a 32-joint SensorSample, 4096: a large one);
//                               the pushers' mutex included: the DDS callback's
//                               whole cost past DDS
//   BM_RingPushWhileReading/832 the same while another thread copies records
//                               out without pause (a window's file being written)
//   BM_RingRead                 batches of 512 KiB copied out of a full ring of
//                               832-byte samples (the writer thread's copy)
//
// items_per_second is samples/s; bytes_per_second payload bytes/s.
//   build/bin/wbi_bench_window_ring --benchmark_format=json
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "window_ring.hpp"

namespace {

using wbi::recording::RingBatch;
using wbi::recording::WindowRing;

constexpr std::size_t kRingBytes = std::size_t{64} << 20;
constexpr std::uint64_t kMs = 1'000'000;

void fill(WindowRing& ring, const std::vector<std::uint8_t>& bytes, std::uint64_t& t) {
  while (ring.stats().pushed_bytes < 2 * ring.capacity()) {  // wrapped: every push evicts
    ring.push(1, t, t, bytes);
    t += kMs / 10;
  }
}

// kReading: while a thread copies records out all along (a window's file
// being written): the reader takes no lock, so this is the cache's cost only.
template <bool kReading>
void push_steadily(benchmark::State& state) {
  const std::vector<std::uint8_t> bytes(static_cast<std::size_t>(state.range(0)), 0x5a);
  WindowRing ring(kRingBytes, 5000 * kMs);
  std::uint64_t t = 1;
  fill(ring, bytes, t);
  std::atomic<bool> stop{false};
  std::thread reader;
  if constexpr (kReading) {
    reader = std::thread([&] {
      RingBatch batch(std::size_t{512} << 10);
      ring.start_reading(0);
      while (!stop.load(std::memory_order_relaxed)) {
        ring.read(batch, UINT64_MAX);
      }
    });
  }
  for (auto _ : state) {
    ring.push(1, t, t, bytes);
    t += kMs / 10;
  }
  stop = true;
  if (reader.joinable()) {
    reader.join();
  }
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(state.iterations() * state.range(0));
}

void BM_RingPush(benchmark::State& state) { push_steadily<false>(state); }
BENCHMARK(BM_RingPush)->Arg(64)->Arg(832)->Arg(4096);

void BM_RingPushWhileReading(benchmark::State& state) { push_steadily<true>(state); }
BENCHMARK(BM_RingPushWhileReading)->Arg(832)->UseRealTime();

void BM_RingRead(benchmark::State& state) {
  const std::vector<std::uint8_t> bytes(832, 0x5a);
  WindowRing ring(kRingBytes, 5000 * kMs);
  RingBatch batch(std::size_t{512} << 10);
  std::uint64_t t = 1;
  fill(ring, bytes, t);
  std::int64_t samples = 0;
  ring.start_reading(0);
  for (auto _ : state) {
    if (ring.read(batch, UINT64_MAX) == WindowRing::ReadEnd::caught_up) {
      state.PauseTiming();
      ring.stop_reading();
      ring.start_reading(0);
      state.ResumeTiming();
    }
    samples += static_cast<std::int64_t>(batch.size());
  }
  state.SetItemsProcessed(samples);
  state.SetBytesProcessed(samples * 832);
}
BENCHMARK(BM_RingRead);

}  // namespace

BENCHMARK_MAIN();
