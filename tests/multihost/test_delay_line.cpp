// The link emulator's delay line on a simulated clock: delays stay within
// delay +- jitter, frames keep their order and bytes, the loss rate matches,
// a full queue drops, bad settings are named.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "link_emulator/delay_line.hpp"

namespace {

using wbi::link_emulator::DelayLine;
using wbi::link_emulator::Impairment;

constexpr std::int64_t kMs = 1'000'000;

// A frame whose first bytes hold its index.
std::array<std::uint8_t, 64> frame(std::uint32_t index) {
  std::array<std::uint8_t, 64> bytes{};
  for (int i = 0; i < 4; ++i) {
    bytes[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(index >> (8 * i));
  }
  return bytes;
}
std::uint32_t index_of(std::span<const std::uint8_t> bytes) {
  std::uint32_t index = 0;
  for (int i = 0; i < 4; ++i) {
    index |= static_cast<std::uint32_t>(bytes[static_cast<std::size_t>(i)]) << (8 * i);
  }
  return index;
}

struct Departure {
  std::uint32_t index;
  std::int64_t at_ns;
};

// Offers `frames` frames, one every `spacing_ns`, and releases in 10 us steps
// until the line is empty; returns what left and when.
std::vector<Departure> run(DelayLine& line, std::uint32_t frames, std::int64_t spacing_ns) {
  std::vector<Departure> departures;
  std::int64_t now = 0;
  std::uint32_t offered = 0;
  while (offered < frames || line.queued() > 0) {
    if (offered < frames && now >= static_cast<std::int64_t>(offered) * spacing_ns) {
      const auto bytes = frame(offered++);
      line.offer(bytes, now);
    }
    line.release(now, [&](std::span<const std::uint8_t> bytes) {
      EXPECT_EQ(bytes.size(), 64u);
      departures.push_back({index_of(bytes), now});
    });
    now += 10'000;
  }
  return departures;
}

TEST(DelayLine, DelaysEveryFrameWithinTheJitterAndKeepsTheirOrder) {
  DelayLine line({2 * kMs, 1 * kMs, 0.0}, 1024, 7);
  const auto departures = run(line, 2000, kMs / 2);
  ASSERT_EQ(departures.size(), 2000u);
  double sum_ms = 0;
  std::int64_t shortest = INT64_MAX, longest = 0;
  for (std::size_t i = 0; i < departures.size(); ++i) {
    ASSERT_EQ(departures[i].index, i) << "frames overtook each other";
    const std::int64_t delay = departures[i].at_ns - static_cast<std::int64_t>(i) * (kMs / 2);
    shortest = std::min(shortest, delay);
    longest = std::max(longest, delay);
    sum_ms += static_cast<double>(delay) / kMs;
  }
  // 1 to 3 ms, plus one 10 us release step; both ends of the range are reached.
  EXPECT_GE(shortest, 1 * kMs);
  EXPECT_LT(shortest, 1 * kMs + kMs / 2);
  EXPECT_LE(longest, 3 * kMs + 10'000);
  EXPECT_GT(longest, 3 * kMs - kMs / 2);
  // No overtaking pushes the mean above 2 ms; it stays within the range.
  EXPECT_GT(sum_ms / 2000, 2.0);
  EXPECT_LT(sum_ms / 2000, 3.0);
  EXPECT_EQ(line.counters().forwarded, 2000u);
}

TEST(DelayLine, LosesTheConfiguredFraction) {
  DelayLine line({kMs, 0, 0.05}, 64, 3);
  const auto departures = run(line, 20000, 100'000);
  const auto& counters = line.counters();
  EXPECT_EQ(counters.lost + counters.forwarded, 20000u);
  EXPECT_EQ(departures.size(), counters.forwarded);
  // 5 % of 20000 = 1000, standard deviation about 31.
  EXPECT_GT(counters.lost, 850u);
  EXPECT_LT(counters.lost, 1150u);
}

TEST(DelayLine, FullQueueDropsAndCounts) {
  DelayLine line({10 * kMs, 0, 0.0}, 4, 1);
  for (std::uint32_t i = 0; i < 6; ++i) {
    line.offer(frame(i), 0);
  }
  EXPECT_EQ(line.queued(), 4u);
  EXPECT_EQ(line.counters().overflow, 2u);
  EXPECT_EQ(line.next_due_ns(), 10 * kMs);
  int released = 0;
  line.release(10 * kMs - 1, [&](std::span<const std::uint8_t>) { ++released; });
  EXPECT_EQ(released, 0) << "a frame left before its delay";
  line.release(10 * kMs, [&](std::span<const std::uint8_t>) { ++released; });
  EXPECT_EQ(released, 4);
  EXPECT_EQ(line.next_due_ns(), -1);
}

TEST(DelayLine, OversizeFramesAreDropped) {
  DelayLine line({0, 0, 0.0}, 4, 1);
  std::vector<std::uint8_t> jumbo(DelayLine::kMaxFrameBytes + 1);
  line.offer(jumbo, 0);
  EXPECT_EQ(line.queued(), 0u);
  EXPECT_EQ(line.counters().oversize, 1u);
}

TEST(DelayLine, BadSettingsAreNamed) {
  auto message = [](const Impairment& impairment, std::size_t slots) {
    try {
      DelayLine line(impairment, slots, 1);
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({-1, 0, 0.0}, 4).find("delay"), std::string::npos);
  EXPECT_NE(message({0, -1, 0.0}, 4).find("jitter"), std::string::npos);
  EXPECT_NE(message({0, 0, 1.5}, 4).find("loss"), std::string::npos);
  EXPECT_NE(message({0, 0, 0.0}, 0).find("slot"), std::string::npos);
}

}  // namespace
