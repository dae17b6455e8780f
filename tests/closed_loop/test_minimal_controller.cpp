// The minimal controller of controllers/README.md ("Writing a controller") as a lab
// uses it: a plugin of its own
// (controllers/examples/minimal_controller.cpp), named by a deploy file and
// found through WBI_PLUGIN_PATH, hosted on the arm in lockstep: switched to
// from hold and back by the host's schedule, a gain changed with `wbi param`
// while it runs, and the arm at its target.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

TEST(MinimalController, HostedFromAPluginSwitchedToAndBackWithALiveGain) {
  const auto bin = wbi::test::binary_dir() / "bin";
  const std::string plugins =
      "WBI_PLUGIN_PATH=" + (wbi::test::binary_dir() / "examples" / "plugins").string();
  wbi::test::ChildProcess launch(
      bin / "wbi",
      {"launch",
       (wbi::test::source_dir() / "controllers" / "examples" / "minimal_pd.yaml").string(),
       "--duration", "60"},
      {plugins});
  ASSERT_TRUE(launch.wait_for_output("switch: hold → minimal at t = 0.500 s", 60s))
      << launch.output();
  wbi::test::ChildProcess set(bin / "wbi",
                              {"param", "set", "minimal", "kp", "80", "--robot", "arm"});
  ASSERT_EQ(set.wait(30s).value_or(-1), 0) << set.output();
  EXPECT_NE(set.output().find("minimal.kp = 80 N m/rad"), std::string::npos) << set.output();
  const auto code = launch.wait(120s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  EXPECT_NE(out.find("switch: minimal → hold at t = 4.000 s; torque step 0.00 %"),
            std::string::npos)
      << out;
  const std::string marker = "minimal_pd: max joint error ";
  const auto at = out.rfind(marker);
  ASSERT_NE(at, std::string::npos) << out;
  // 3.5 s of PD at kp 60 then 80 from hold's posture (measured: see the test's output).
  const double error = std::stod(out.substr(at + marker.size()));
  std::printf("minimal_pd: max joint error %.4f rad\n", error);
  EXPECT_LT(error, 0.05) << out;
}

}  // namespace
