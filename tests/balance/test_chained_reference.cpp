// A planner chained in the balancer's host (issue 53, controllers/README.md,
// "Chaining") against the same reference from a component over DDS: the CoM
// sinusoid's points reach the balancer either way for the state it answers,
// so the balancing ends on the same figure to the printed digit. The
// project's humanoid (deploy/balance.yaml, balance_chained.yaml) and iCub 3
// (icub3_balance.yaml, icub3_balance_chained.yaml; ../shared).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

// The launch's last "com tracking rms: X m" line, as printed.
std::string rms_line(const std::string& deploy) {
  wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                                 {"launch", (wbi::test::source_dir() / "deploy" / deploy).string(),
                                  "--one-process", "--duration", "200"});
  const auto code = launch.wait(240s);
  const std::string out = launch.output();
  EXPECT_EQ(code.value_or(-1), 0) << out;
  const auto at = out.rfind("com tracking rms: ");
  return at == std::string::npos ? "none" : out.substr(at, out.find('\n', at) - at);
}

struct Pair {
  const char* topic;    // the reference from a component, over DDS
  const char* chained;  // from a planner in the balancer's host
  bool shared;          // needs ../shared/models
};

class ChainedReference : public ::testing::TestWithParam<Pair> {};

TEST_P(ChainedReference, GivesTheFigureOfTheTopicRoute) {
  if (GetParam().shared && !wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  const std::string topic = rms_line(GetParam().topic);
  const std::string chained = rms_line(GetParam().chained);
  std::printf("%s: %s\n%s: %s\n", GetParam().topic, topic.c_str(), GetParam().chained,
              chained.c_str());
  EXPECT_NE(topic, "none");
  EXPECT_EQ(chained, topic);
}

INSTANTIATE_TEST_SUITE_P(Robots, ChainedReference,
                         ::testing::Values(Pair{"balance.yaml", "balance_chained.yaml", false},
                                           Pair{"icub3_balance.yaml", "icub3_balance_chained.yaml",
                                                true}));

}  // namespace
