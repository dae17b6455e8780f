// A sensor sample crosses between two real processes on loopback: the talker
// process publishes pattern samples, this process checks every one.
#include <gtest/gtest.h>

#include <chrono>

#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "child_process.hpp"
#include "sample_pattern.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

TEST(DdsTwoProcesses, EverySampleArrivesIntact) {
  constexpr std::uint64_t kCount = 200;
  wbi::dds::Participant participant("listener");
  std::vector<std::uint64_t> seen;
  std::string first_mismatch;
  wbi::dds::Subscriber<wbi::msg::SensorSample> subscriber(
      participant, wbi::dds::topics::sensors("twoproc"), wbi::dds::qos::kLatched,
      [&](const wbi::msg::SensorSample& sample, const wbi::dds::detail::SampleInfo&) {
        seen.push_back(sample.header().seq());
        if (first_mismatch.empty()) {
          first_mismatch = wbi::test::pattern_mismatch(sample, "twoproc");
        }
      });
  wbi::test::ChildProcess talker(wbi::test::binary_dir() / "tests" / "wbi_test_talker",
                                 {"twoproc", std::to_string(kCount)});
  ASSERT_TRUE(subscriber.wait_for_publishers(1, 20s)) << talker.output();
  const auto code = talker.wait(60s);
  ASSERT_TRUE(code.has_value()) << "talker did not finish: " << talker.output();
  EXPECT_EQ(*code, 0) << talker.output();

  wbi::dds::Received<wbi::msg::SensorSample> last;
  ASSERT_TRUE(subscriber.wait_newer(last, kCount - 1, 5s))
      << "received " << subscriber.count() << " samples, callback saw " << seen.size()
      << (seen.empty() ? std::string()
                       : ", first seq " + std::to_string(seen.front()) + ", last " +
                             std::to_string(seen.back()));
  EXPECT_EQ(first_mismatch, "");
  ASSERT_EQ(seen.size(), kCount);
  for (std::uint64_t i = 0; i < kCount; ++i) {
    ASSERT_EQ(seen[i], i);
  }
}

}  // namespace
