// One robot, one name: the demo launched twice on one domain gives one good run
// and one clear refusal; two robots of one name started at the same instant
// end with exactly one running.
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

const std::string kRefusal = "robot 'arm' is already running on DDS domain";

std::string demo() { return (wbi::test::source_dir() / "deploy" / "demo.yaml").string(); }

TEST(RobotName, TheDemoLaunchedTwiceRefusesTheSecondAndTheFirstRunsOn) {
  const auto wbi = wbi::test::binary_dir() / "bin" / "wbi";
  ChildProcess first(wbi, {"launch", demo(), "--duration", "8"});
  ASSERT_TRUE(first.wait_for_output("[controller] t = ", 60s)) << first.output();
  const std::string marker = "[launch] robot: started (pid ";
  const auto at = first.output().find(marker);
  ASSERT_NE(at, std::string::npos) << first.output();
  const std::string robot_pid =
      std::to_string(std::stoi(first.output().substr(at + marker.size())));

  ChildProcess second(wbi, {"launch", demo(), "--duration", "8"});
  const auto refused = second.wait(30s);
  ASSERT_TRUE(refused.has_value()) << second.output();
  const std::string out = second.output();
  EXPECT_EQ(*refused, 1) << out;
  EXPECT_NE(out.find(kRefusal), std::string::npos) << out;
  EXPECT_NE(out.find("pid " + robot_pid), std::string::npos) << "the other robot is not named\n"
                                                             << out;
  EXPECT_NE(out.find("estimator: not started"), std::string::npos)
      << "the second deployment started more than its robot\n"
      << out;

  const auto code = first.wait(60s);
  ASSERT_TRUE(code.has_value()) << first.output();
  EXPECT_EQ(*code, 0) << first.output();
  const std::string final_marker = "\nfinal max joint error: ";
  const auto final_at = first.output().rfind(final_marker);
  ASSERT_NE(final_at, std::string::npos) << first.output();
  // The real-time demo settles at 0.0003-0.002 rad (0.00115 seen with the suite
  // at ctest -j4 on 2 cores); a second robot mixed in would throw it far off.
  EXPECT_LT(std::stod(first.output().substr(final_at + final_marker.size())), 0.01)
      << first.output();
}

TEST(RobotName, TwoRobotsStartedTogetherEndWithOneRunning) {
  const auto host = wbi::test::binary_dir() / "bin" / "wbi_host";
  ChildProcess a(host, {demo(), "--process", "robot"});
  ChildProcess b(host, {demo(), "--process", "robot"});
  // The loser leaves after its name check; the winner runs until stopped.
  const auto deadline = std::chrono::steady_clock::now() + 30s;
  while (a.running() && b.running() && std::chrono::steady_clock::now() < deadline) {
    a.wait(50ms);  // polling two processes: whichever ends first
  }
  ASSERT_NE(a.running(), b.running()) << "a:\n" << a.output() << "\nb:\n" << b.output();
  ChildProcess& loser = a.running() ? b : a;
  ChildProcess& winner = a.running() ? a : b;
  EXPECT_NE(loser.output().find(kRefusal), std::string::npos) << loser.output();
  EXPECT_TRUE(winner.wait_for_output("wbi_host: running", 30s)) << winner.output();
  EXPECT_TRUE(winner.running()) << winner.output();
}

}  // namespace
