// The balancing demo as a user runs it: `wbi launch deploy/balance.yaml` starts
// the simulated humanoid, the estimator and the momentum-based balancing
// controller as three processes in lockstep; the CoM follows the lateral
// sinusoid for 20 s and the launch ends with "com tracking rms: X m".
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "child_process.hpp"
#include "progress_lines.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

TEST(BalanceLaunch, ThreeProcessesTrackTheSinusoidFor20Seconds) {
  // The controller ends the run after 21 s of robot time (exit_after_s); --duration
  // is only a safety net.
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / "balance.yaml").string(), "--duration",
       "150"});
  const auto code = launch.wait(170s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  const auto times = wbi::test::progress_times(out);
  ASSERT_GE(times.size(), 10u) << "no progress lines\n" << out;
  EXPECT_GE(times.back(), 20.0) << "the run ended early\n" << out;
  EXPECT_NE(out.find("[controller] qp failures: 0\n"), std::string::npos) << out;
  const std::string marker = "\ncom tracking rms: ";
  const auto at = out.rfind(marker);
  ASSERT_NE(at, std::string::npos) << out;
  const auto end = out.find(" m", at + 1);
  ASSERT_EQ(out.find('\n', end), out.size() - 1) << "the rms is not the last line:\n" << out;
  // The bound; the run gives about 1.5 mm.
  EXPECT_LT(std::stod(out.substr(at + marker.size())), 0.01) << out;
}

}  // namespace
