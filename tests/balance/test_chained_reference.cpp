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
#include <vector>

#include "child_process.hpp"
#include "lockstep_fallbacks.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

// One launch: its last "com tracking rms: X m" line, as printed ("none" if
// it has none), the balancer's count of reference points (the figures are
// taken at exit_after_s: the ticks answered while the process shuts down,
// as many as the machine's timing allows, do not count), and the
// wall-clock fallbacks it reached.
struct LaunchRun {
  std::string rms = "none";
  std::string points = "none";
  std::vector<std::string> fallbacks;
};

LaunchRun run_once(const std::string& deploy) {
  wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                                 {"launch", (wbi::test::source_dir() / "deploy" / deploy).string(),
                                  "--one-process", "--duration", "200"});
  const auto code = launch.wait(240s);
  const std::string out = launch.output();
  EXPECT_EQ(code.value_or(-1), 0) << out;
  LaunchRun run;
  run.fallbacks = wbi::test::lockstep_fallbacks(out);
  if (const auto at = out.rfind("com tracking rms: "); at != std::string::npos) {
    run.rms = out.substr(at, out.find('\n', at) - at);
  }
  if (const auto at = out.rfind("reference balance/com: "); at != std::string::npos) {
    run.points = out.substr(at, out.find(" points", at) - at);
  }
  std::printf("%s: %s%s\n", deploy.c_str(), run.rms.c_str(),
              run.fallbacks.empty() ? "" : " (reached a wall-clock fallback)");
  return run;
}

struct Pair {
  const char* topic;    // the reference from a component, over DDS
  const char* chained;  // from a planner in the balancer's host
  bool shared;          // needs ../shared/models
};

class ChainedReference : public ::testing::TestWithParam<Pair> {};

// Equal figures are required of two runs that reached no wall-clock fallback.
// A pair that differs where one of them reached a fallback (a reference point
// late on a busy machine: deploy/README.md, "Reproducible lockstep") is run
// again, three pairs at most.
TEST_P(ChainedReference, GivesTheFigureOfTheTopicRoute) {
  if (GetParam().shared && !wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  for (int pair = 1; pair <= 3; ++pair) {
    const LaunchRun topic = run_once(GetParam().topic);
    const LaunchRun chained = run_once(GetParam().chained);
    ASSERT_NE(topic.rms, "none");
    ASSERT_NE(topic.points, "none");
    if (chained.rms == topic.rms && chained.points == topic.points) {
      return;
    }
    ASSERT_FALSE(topic.fallbacks.empty() && chained.fallbacks.empty())
        << "the routes differ and neither run reached a wall-clock fallback: " << chained.rms
        << ", " << chained.points << " against " << topic.rms << ", " << topic.points;
    std::printf("pair %d differs where a run reached a fallback: run again\n", pair);
  }
  ADD_FAILURE() << "three pairs differed, each with a run that reached a wall-clock fallback";
}

INSTANTIATE_TEST_SUITE_P(Robots, ChainedReference,
                         ::testing::Values(Pair{"balance.yaml", "balance_chained.yaml", false},
                                           Pair{"icub3_balance.yaml", "icub3_balance_chained.yaml",
                                                true}));

}  // namespace
