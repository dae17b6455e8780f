// The controller host driven from other processes: `wbi launch` runs the arm
// with a host of two controllers; `wbi controller` and `wbi param` (each a
// process of its own; some without --robot: the arm is the only robot) list
// them, refuse what cannot be done with one line and no change, set a gain,
// and switch the arm to hold.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

struct Outcome {
  int code = -1;
  std::string output;
};

// One `wbi` command against the launched robot, bounded in time; with
// name_robot false, without --robot (the arm is the only robot on the domain).
Outcome wbi_command(std::vector<std::string> args, bool name_robot = true) {
  if (name_robot) {
    args.push_back("--robot");
    args.push_back("arm");
  }
  wbi::test::ChildProcess command(wbi::test::binary_dir() / "bin" / "wbi", args);
  const auto code = command.wait(30s);
  return {code.value_or(-1), command.output()};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ControllerCli, ListSetRefuseAndSwitchWhileTheArmRuns) {
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / "arm_controller_host.yaml").string(),
       "--duration", "60"});
  ASSERT_TRUE(launch.wait_for_output("max joint error", 60s)) << launch.output();

  const auto list = wbi_command({"controller", "list"}, false);
  ASSERT_EQ(list.code, 0) << list.output;
  EXPECT_TRUE(contains(list.output, "using robot 'arm', the only one with a controller host"))
      << list.output;
  EXPECT_TRUE(contains(list.output, "* pd  [pd_gravity]  active")) << list.output;
  EXPECT_TRUE(contains(list.output, "  hold  [hold]  inactive")) << list.output;

  const auto too_big = wbi_command({"param", "set", "pd", "gain_scale", "20"});
  EXPECT_EQ(too_big.code, 1) << too_big.output;
  EXPECT_TRUE(contains(too_big.output, "refused: pd: gain_scale = 20 is outside [0, 10]"))
      << too_big.output;
  const auto not_live = wbi_command({"param", "set", "pd", "bandwidth_hz", "3"});
  EXPECT_EQ(not_live.code, 1) << not_live.output;
  EXPECT_TRUE(contains(not_live.output, "cannot change while the controller is active"))
      << not_live.output;

  const auto halved = wbi_command({"param", "set", "pd", "gain_scale", "0.5"}, false);
  ASSERT_EQ(halved.code, 0) << halved.output;
  EXPECT_TRUE(contains(halved.output, "pd.gain_scale = 0.5")) << halved.output;
  const auto get = wbi_command({"param", "get", "pd", "gain_scale"});
  ASSERT_EQ(get.code, 0) << get.output;
  EXPECT_TRUE(contains(get.output, "gain_scale = 0.5")) << get.output;
  // The latched topic carries the new value, for a recording.
  wbi::test::ChildProcess echo(wbi::test::binary_dir() / "bin" / "wbi",
                               {"topic", "echo", "wbi/arm/controllers/parameters", "--count", "1"});
  ASSERT_TRUE(echo.wait(30s).has_value());
  EXPECT_TRUE(contains(echo.output(), "gain_scale")) << echo.output();

  const auto unknown =
      wbi_command({"controller", "switch", "--activate", "balance", "--deactivate", "pd"});
  EXPECT_EQ(unknown.code, 1) << unknown.output;
  EXPECT_TRUE(contains(unknown.output, "refused: unknown controller 'balance' (hosted: pd, hold)"))
      << unknown.output;
  const auto still = wbi_command({"controller", "list"});
  EXPECT_TRUE(contains(still.output, "* pd")) << "a refused switch changes nothing\n"
                                              << still.output;

  const auto to_hold =
      wbi_command({"controller", "switch", "--activate", "hold", "--deactivate", "pd"});
  ASSERT_EQ(to_hold.code, 0) << to_hold.output;
  EXPECT_TRUE(contains(to_hold.output, "switched pd → hold at t = ")) << to_hold.output;
  const auto after = wbi_command({"controller", "list"});
  EXPECT_TRUE(contains(after.output, "* hold  [hold]  active")) << after.output;

  launch.stop();
}

}  // namespace
