// One producer per stream and one owner per joint, end to end: the lockstep
// demo run next to a rogue ends exactly as without it (the controller's final
// error to 9 digits, in lockstep a function of every applied command and
// sensor sample), and the rogue is named where it was dropped:
//  - a rogue that publishes well-formed sensor samples for 'arm', started
//    before the robot (so it is the first writer heard): named in the log of
//    each process that dropped its samples;
//  - a rogue that streams 40 N·m to joint_1, which the PD controller claimed:
//    the robot refuses its commands, counts them and names the owner.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

struct DemoRun {
  int code = -1;
  std::string output;
  std::string final_error;  // as printed: "%.9g"
};

DemoRun run_demo() {
  const auto wbi = wbi::test::binary_dir() / "bin" / "wbi";
  const auto deploy = wbi::test::source_dir() / "deploy" / "demo_lockstep.yaml";
  ChildProcess launch(wbi, {"launch", deploy.string(), "--duration", "20"});
  DemoRun run;
  const auto code = launch.wait(60s);
  run.output = launch.output();
  if (!code) {
    return run;
  }
  run.code = *code;
  const std::string marker = "final max joint error: ";
  const auto at = run.output.rfind(marker);
  if (at != std::string::npos) {
    run.final_error = run.output.substr(
        at + marker.size(), run.output.find(' ', at + marker.size()) - at - marker.size());
  }
  return run;
}

// The demo run beside a rogue (wbi_test_rogue ARGS), started first.
struct RogueRun {
  bool rogue_started = false;  // it said it was publishing
  bool rogue_lived = false;    // it was still running when the demo ended
  pid_t rogue_pid = 0;
  std::string rogue_output;
  DemoRun demo;
};

RogueRun run_beside_rogue(const std::vector<std::string>& args) {
  ChildProcess rogue(wbi::test::binary_dir() / "tests" / "wbi_test_rogue", args);
  RogueRun run;
  run.rogue_pid = rogue.pid();
  run.rogue_started = rogue.wait_for_output("rogue: publishing", 20s);
  if (run.rogue_started) {
    run.demo = run_demo();
    run.rogue_lived = rogue.running();
  }
  rogue.stop(SIGTERM, 10s);
  run.rogue_output = rogue.output();
  return run;
}

class Rogue : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { alone_ = new DemoRun(run_demo()); }
  static void TearDownTestSuite() { delete alone_; }
  // The demo without any rogue: what every run beside one must end with.
  static const DemoRun& alone() { return *alone_; }

 private:
  static inline DemoRun* alone_ = nullptr;
};

TEST_F(Rogue, ASensorPublisherChangesNothingAndIsNamed) {
  ASSERT_EQ(alone().code, 0) << alone().output;
  ASSERT_FALSE(alone().final_error.empty()) << alone().output;

  const RogueRun run = run_beside_rogue({"arm", "sensors", "7"});
  ASSERT_TRUE(run.rogue_started) << run.rogue_output;
  EXPECT_TRUE(run.rogue_lived) << run.rogue_output;
  const DemoRun& beside = run.demo;

  ASSERT_EQ(beside.code, 0) << beside.output;
  EXPECT_EQ(beside.final_error, alone().final_error) << "the rogue's samples changed the run\n"
                                                     << beside.output;
  const std::string named = "dropping the samples of a second writer, participant 'rogue'";
  EXPECT_NE(beside.output.find("[estimator] wbi: 'wbi/arm/sensors': " + named), std::string::npos)
      << "the estimator did not name the rogue\n"
      << beside.output;
  // pd_gravity reads the state only: its proxy never subscribes to the raw
  // samples (they are subscribed to at their first read), so it meets no rogue.
  EXPECT_EQ(beside.output.find("[controller] wbi: 'wbi/arm/sensors'"), std::string::npos)
      << beside.output;
  EXPECT_NE(beside.output.find("pid " + std::to_string(run.rogue_pid)), std::string::npos)
      << beside.output;
}

TEST_F(Rogue, ACommandPublisherNeverMovesAClaimedJoint) {
  ASSERT_EQ(alone().code, 0) << alone().output;
  ASSERT_FALSE(alone().final_error.empty()) << alone().output;

  const RogueRun run = run_beside_rogue({"arm", "commands", "0", "40"});
  ASSERT_TRUE(run.rogue_started) << run.rogue_output;
  EXPECT_TRUE(run.rogue_lived) << run.rogue_output;
  const DemoRun& beside = run.demo;

  ASSERT_EQ(beside.code, 0) << beside.output;
  EXPECT_EQ(beside.final_error, alone().final_error) << "the rogue's 40 N·m reached joint_1\n"
                                                     << beside.output;
  EXPECT_NE(beside.output.find("[robot] claims: 'pd_gravity' (participant"), std::string::npos)
      << beside.output;
  EXPECT_NE(beside.output.find("[robot] command from 'rogue' rejected: joint 'joint_1' is held "
                               "by 'pd_gravity'"),
            std::string::npos)
      << "the robot did not name the rogue and the owner\n"
      << beside.output;
}

}  // namespace
