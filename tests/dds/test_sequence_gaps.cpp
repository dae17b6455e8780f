// The samples a reader lost, counted from the gaps in each writer's sequence
// numbers (dds/src/sequence_gaps.hpp): per writer, from the first sample heard.
#include <gtest/gtest.h>

#include <cstdint>

#include "sequence_gaps.hpp"

namespace {

using wbi::dds::detail::Guid;
using wbi::dds::detail::SequenceGaps;

Guid writer(std::uint8_t id) {
  Guid guid{};
  guid[15] = id;
  return guid;
}

TEST(SequenceGaps, ConsecutiveSamplesLoseNothing) {
  SequenceGaps gaps;
  for (std::uint64_t sequence = 1; sequence <= 100; ++sequence) {
    gaps.observe(writer(1), sequence);
  }
  EXPECT_EQ(gaps.lost(), 0u);
}

TEST(SequenceGaps, ASkippedRunIsCountedAndALateJoinersStartIsNot) {
  SequenceGaps gaps;
  gaps.observe(writer(1), 50);  // joined late: 1-49 were never its to lose
  gaps.observe(writer(1), 51);
  gaps.observe(writer(1), 55);  // 52, 53, 54
  gaps.observe(writer(1), 54);  // out of order: neither lost nor found again
  gaps.observe(writer(1), 56);
  EXPECT_EQ(gaps.lost(), 3u);
}

TEST(SequenceGaps, EachWriterIsFollowedOnItsOwn) {
  SequenceGaps gaps;
  gaps.observe(writer(1), 1);
  gaps.observe(writer(2), 10);
  gaps.observe(writer(1), 3);  // 2
  gaps.observe(writer(2), 11);
  gaps.observe(writer(2), 20);  // 12-19
  EXPECT_EQ(gaps.lost(), 9u);
}

TEST(SequenceGaps, AWriterBeyondTheFollowedOnesReplacesTheLeastRecentlyHeard) {
  SequenceGaps gaps;
  for (std::uint8_t id = 1; id <= SequenceGaps::kWriters; ++id) {
    gaps.observe(writer(id), 1);
  }
  for (std::uint8_t id = 2; id <= SequenceGaps::kWriters; ++id) {
    gaps.observe(writer(id), 2);  // writer 1 is now the least recently heard
  }
  gaps.observe(writer(100), 1);  // takes writer 1's place
  gaps.observe(writer(2), 4);    // still followed: 3 is lost
  gaps.observe(writer(1), 10);   // starts again: 2-9 not counted
  gaps.observe(writer(1), 11);
  EXPECT_EQ(gaps.lost(), 1u);
}

}  // namespace
