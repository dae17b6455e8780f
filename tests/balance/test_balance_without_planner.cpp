// A figure computed over nothing is not a result: deploy/balance_planner.yaml
// launched without its planner (python/examples/com_planner.py) receives no
// CoM reference point, so its CoM tracking figures say "none", the controller
// ends its run with kExitRunFailed (65) and `wbi launch` exits 1 naming it.
// (Before, the run printed "com tracking rms: 0.000000 m" and exited 0.)
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "child_process.hpp"
#include "deploy_text.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(BalanceWithoutPlanner, FailsInsteadOfReportingAPerfectFigure) {
  std::string text = wbi::test::deploy_text("balance_planner.yaml");
  ASSERT_EQ(wbi::test::replace_all(text, "exit_after_s: 21.0", "exit_after_s: 2.0"), 1) << text;
  const auto deploy = wbi::test::write_test_file("balance_without_planner.yaml", text);
  wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                                 {"launch", deploy.string(), "--duration", "60"});
  const auto code = launch.wait(90s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 1) << out;
  EXPECT_TRUE(contains(out,
                       "[controller] com tracking rms: none (no CoM reference point came on "
                       "balance/com"))
      << out;
  EXPECT_TRUE(contains(out, "[controller] max com error: none")) << out;
  EXPECT_TRUE(contains(out, "controller: failed with exit code 65 (its run failed its checks)"))
      << out;
  EXPECT_TRUE(contains(out, "controller: not respawned")) << out;
  EXPECT_TRUE(contains(out, "controller: exit code 65: FAILED, its run failed its checks")) << out;
  EXPECT_FALSE(contains(out, "com tracking rms: 0.")) << out;
}

}  // namespace
