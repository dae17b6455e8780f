// The README's main job, as a user runs it: `wbi launch deploy/demo.yaml`
// starts the robot, the estimator, the model service and the controller (with
// the remote model) as four processes; the arm reaches its target and the
// launch ends with the final error.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "child_process.hpp"
#include "progress_lines.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

TEST(DemoLaunch, FourProcessesBringTheArmToItsTarget) {
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / "demo.yaml").string(), "--duration", "6"});
  const auto code = launch.wait(120s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  for (const char* process : {"robot", "estimator", "model_service", "controller"}) {
    EXPECT_NE(out.find(std::string("[launch] ") + process + ": started"), std::string::npos) << out;
  }
  // Progress lines come once a second of controller time; their exact stamp
  // depends on when the first state arrived, so only their times are checked.
  const auto times = wbi::test::progress_times(out);
  ASSERT_GE(times.size(), 2u) << "no progress lines\n" << out;
  EXPECT_GE(times.back(), 1.0) << out;
  const std::string marker = "\nfinal max joint error: ";
  const auto at = out.rfind(marker);
  ASSERT_NE(at, std::string::npos) << out;
  const auto end = out.find(" rad", at);
  ASSERT_EQ(out.find('\n', end), out.size() - 1) << "the error is not the last line:\n" << out;
  const double error = std::stod(out.substr(at + marker.size()));
  EXPECT_LT(error, 0.01) << out;
}

}  // namespace
