// The windowed recorder's parts without DDS: the ring (bounded bytes, order,
// wrap-around, eviction counted, the reader's cursor and its losses, no
// allocation per sample), its command-line words and its file names.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include <wbi/recording/window_recorder.hpp>

#include "allocation_counter.hpp"
#include "window_ring.hpp"

namespace {

using wbi::EventKind;
using wbi::recording::RingBatch;
using wbi::recording::WindowRing;

constexpr std::uint64_t kMs = 1'000'000;

// Sample k: `size` bytes of value k, logged at k ms.
std::vector<std::uint8_t> payload(std::uint64_t k, std::size_t size) {
  return std::vector<std::uint8_t>(size, static_cast<std::uint8_t>(k));
}

bool push(WindowRing& ring, std::uint64_t k, std::size_t size) {
  const auto bytes = payload(k, size);
  return ring.push(static_cast<std::uint32_t>(k % 7), k * kMs, k * kMs + 1, bytes);
}

// Reads everything from `from` on; checks each record against what was pushed.
std::vector<std::uint64_t> read_all(WindowRing& ring, std::uint64_t from,
                                    std::uint64_t until = UINT64_MAX) {
  RingBatch batch(1 << 20);
  std::vector<std::uint64_t> seen;
  ring.start_reading(from);
  for (;;) {
    const auto end = ring.read(batch, until);
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const auto entry = batch[i];
      const std::uint64_t k = entry.sample.log_time / kMs;
      EXPECT_EQ(entry.sample.publish_time, k * kMs + 1);
      EXPECT_EQ(entry.sample.source, k % 7);
      for (const auto byte : entry.bytes) {
        EXPECT_EQ(byte, static_cast<std::uint8_t>(k)) << "sample " << k;
      }
      seen.push_back(k);
    }
    if (end != WindowRing::ReadEnd::batch_full) {
      break;
    }
  }
  ring.stop_reading();
  return seen;
}

TEST(WindowRing, HoldsTheNewestSamplesWithinItsBytesAcrossManyWrapArounds) {
  WindowRing ring(64 * 1024, 0);
  std::mt19937 random(7);
  std::uniform_int_distribution<std::size_t> size(0, 3000);
  for (std::uint64_t k = 0; k < 20000; ++k) {
    ASSERT_TRUE(push(ring, k, size(random)));
    ASSERT_LE(ring.stats().used_bytes, ring.capacity());
  }
  const auto stats = ring.stats();
  const auto seen = read_all(ring, 0);
  ASSERT_EQ(seen.size(), stats.records);
  ASSERT_GT(seen.size(), 20u);
  for (std::size_t i = 0; i < seen.size(); ++i) {  // the newest, consecutive, in order
    EXPECT_EQ(seen[i], 20000 - seen.size() + i);
  }
  EXPECT_EQ(stats.oldest_log_time, seen.front() * kMs);
}

TEST(WindowRing, ReadsFromATimeUntilATimeAndGoesOnWithWhatArrivesLater) {
  WindowRing ring(1 << 20, 0);
  for (std::uint64_t k = 1; k <= 100; ++k) {
    push(ring, k, 100);
  }
  RingBatch batch(1 << 20);
  ring.start_reading(40 * kMs);
  EXPECT_EQ(ring.read(batch, 60 * kMs), WindowRing::ReadEnd::past_until);
  ASSERT_EQ(batch.size(), 21u);
  EXPECT_EQ(batch[0].sample.log_time, 40 * kMs);
  EXPECT_EQ(batch[20].sample.log_time, 60 * kMs);
  // A trigger extends the window: the record left at the boundary comes next.
  EXPECT_EQ(ring.read(batch, 200 * kMs), WindowRing::ReadEnd::caught_up);
  EXPECT_EQ(batch.size(), 40u);
  push(ring, 101, 100);
  EXPECT_EQ(ring.read(batch, 200 * kMs), WindowRing::ReadEnd::caught_up);
  ASSERT_EQ(batch.size(), 1u);
  EXPECT_EQ(batch[0].sample.log_time, 101 * kMs);
}

TEST(WindowRing, ACaughtUpReaderFollowsAcrossTheWrapAndCountsWhatItMissed) {
  WindowRing ring(16 * 1024, 0);
  RingBatch batch(1 << 20);
  std::uint64_t k = 0;
  ring.start_reading(0);
  std::uint64_t expected = 0;
  // Read after every few pushes: every sample, in order, many wraps.
  for (int round = 0; round < 500; ++round) {
    for (int i = 0; i < 3; ++i) {
      push(ring, k++, 200 + 37 * static_cast<std::size_t>(round % 11));
    }
    ASSERT_EQ(ring.read(batch, UINT64_MAX), WindowRing::ReadEnd::caught_up);
    for (std::size_t i = 0; i < batch.size(); ++i) {
      ASSERT_EQ(batch[i].sample.log_time, expected++ * kMs);
    }
  }
  EXPECT_EQ(ring.lost_to_reader(), 0u);
  // A reader that falls behind by more than the ring loses the oldest, counted.
  for (int i = 0; i < 200; ++i) {
    push(ring, k++, 500);
  }
  ASSERT_EQ(ring.read(batch, UINT64_MAX), WindowRing::ReadEnd::caught_up);
  EXPECT_EQ(ring.lost_to_reader() + batch.size(), 200u);
  EXPECT_GT(ring.lost_to_reader(), 0u);
  EXPECT_EQ(batch[batch.size() - 1].sample.log_time, (k - 1) * kMs);
}

TEST(WindowRing, CountsEvictionsInsideTheWindowAndRefusesHugeSamples) {
  WindowRing small(8 * 1024, 50 * kMs);  // must reach 50 ms back: 1 KiB a ms does not fit
  for (std::uint64_t k = 0; k < 100; ++k) {
    push(small, k, 1024);
  }
  EXPECT_GT(small.stats().evicted_in_window, 0u);
  WindowRing roomy(1 << 20, 50 * kMs);
  for (std::uint64_t k = 0; k < 3000; ++k) {
    push(roomy, k, 1024);
  }
  EXPECT_EQ(roomy.stats().evicted_in_window, 0u);  // only samples older than 50 ms were evicted
  EXPECT_FALSE(push(small, 1000, small.max_payload() + 1));
  EXPECT_EQ(small.stats().too_large, 1u);
}

// The reader takes no lock: while a thread pushes (sizes varying, the ring
// wrapping every few hundred samples), every record it copies out is whole
// (its bytes all say its number), in order, and what it misses is counted.
TEST(WindowRing, AReaderWithoutTheLockGetsWholeRecordsOrCountsThemLost) {
  WindowRing ring(64 * 1024, 0);
  constexpr std::uint64_t kSamples = 200000;
  // Reading starts before the first push: records evicted before start_reading()
  // are not the reader's to lose (CI under load saw the pusher 128k records ahead).
  ring.start_reading(0);
  std::thread pusher([&] {
    for (std::uint64_t k = 0; k < kSamples; ++k) {
      push(ring, k, 16 + (k * 37) % 900);
    }
  });
  RingBatch batch(16 * 1024);
  std::uint64_t read = 0;
  std::uint64_t next = 0;
  bool torn = false;
  while (next < kSamples && !torn) {
    ring.read(batch, UINT64_MAX);
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const auto entry = batch[i];
      const std::uint64_t k = entry.sample.log_time / kMs;
      torn = torn || k < next || entry.bytes.size() != 16 + (k * 37) % 900;
      for (const auto byte : entry.bytes) {
        torn = torn || byte != static_cast<std::uint8_t>(k);
      }
      next = k + 1;
      ++read;
    }
    if (ring.stats().pushed == kSamples && batch.size() == 0) {
      break;
    }
  }
  pusher.join();
  while (ring.read(batch, UINT64_MAX) != WindowRing::ReadEnd::caught_up || batch.size() > 0) {
    read += batch.size();
  }
  EXPECT_FALSE(torn);
  EXPECT_EQ(read + ring.lost_to_reader(), kSamples) << "read " << read;
  EXPECT_GT(read, 0u);
}

TEST(WindowRing, PushAllocatesNothing) {
  WindowRing ring(256 * 1024, 0);
  const auto bytes = payload(1, 700);
  const long before = wbi::test::allocation_count();
  for (std::uint64_t k = 0; k < 10000; ++k) {
    ring.push(1, k, k, bytes);
  }
  EXPECT_EQ(wbi::test::allocation_count(), before);
}

TEST(WindowOptions, ParsesWindowsAndTriggerKindsAndNamesWhatIsWrong) {
  using namespace std::chrono_literals;
  const auto span = wbi::recording::parse_window("5:2");
  EXPECT_EQ(span.before, 5s);
  EXPECT_EQ(span.after, 2s);
  EXPECT_EQ(wbi::recording::parse_window("0.5:0").before, 500ms);
  for (const char* bad :
       {"5", "5x2", ":2", "5:", "-1:2", "0:0", "a:b", "5:2:1", "1e9:1", "nan:1"}) {
    try {
      wbi::recording::parse_window(bad);
      ADD_FAILURE() << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(wbi::recording::parse_trigger_kinds("watchdog_trip,LIFECYCLE,Lifecycle"),
            (std::vector<EventKind>{EventKind::watchdog_trip, EventKind::lifecycle}));
  try {
    wbi::recording::parse_trigger_kinds("LIFECYCLE,WATCHDOG");
    ADD_FAILURE() << "WATCHDOG was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'WATCHDOG'"), std::string::npos) << e.what();
  }
  EXPECT_THROW(wbi::recording::parse_trigger_kinds(""), std::invalid_argument);
}

TEST(WindowOptions, FileNamesCarryTheTimeAndKindAndSortByTime) {
  // 2026-11-27 23:55:13.123456789 UTC
  EXPECT_EQ(wbi::recording::window_file_name(1795823713123456789ull, EventKind::watchdog_trip),
            "20261127-235513.123_WATCHDOG_TRIP.mcap");
}

TEST(WindowOptions, TheMemoryPlanAddsUpToTheBoundAndRefusesTooLittle) {
  const auto plan = wbi::recording::window_memory(64u << 20);
  EXPECT_EQ(plan.total(), 64u << 20);
  EXPECT_GT(plan.ring_bytes, 40u << 20);
  EXPECT_THROW(wbi::recording::window_memory(4u << 20), std::invalid_argument);
  EXPECT_EQ(wbi::recording::window_bytes_needed(1e6, std::chrono::seconds(5)), 6'000'000u);
}

}  // namespace
