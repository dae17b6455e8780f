// The PD + gravity controller in one main() (controllers/examples; controllers/README.md,
// "A controller as a plain program") against
// the demo's robot and estimator, each in its own process: it brings the arm
// to its target.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "child_process.hpp"
#include "progress_lines.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

TEST(Example, ReadmePdGravityReachesItsTarget) {
  const auto bin = wbi::test::binary_dir() / "bin";
  const auto demo = (wbi::test::source_dir() / "deploy" / "demo.yaml").string();
  ChildProcess robot(bin / "wbi_host", {demo, "--process", "robot"});
  ChildProcess estimator(bin / "wbi_host", {demo, "--process", "estimator"});
  // 8 s of estimates: started with the robot, the first second or two go to
  // discovery and the 5 Hz approach (2-3 s to 0.01 rad, then 0.0004-0.005 rad).
  ChildProcess controller(bin / "wbi_example_pd_gravity",
                          {(wbi::test::source_dir() / "models" / "arm7.urdf").string(), "8000"});
  const auto code = controller.wait(90s);
  const std::string out = controller.output();
  ASSERT_TRUE(code.has_value()) << out;
  EXPECT_EQ(*code, 0) << out;
  const auto error = wbi::test::last_value_after(out, "final max joint error: ");
  ASSERT_TRUE(error.has_value()) << out;
  EXPECT_LT(*error, 0.02) << out;
}

}  // namespace
