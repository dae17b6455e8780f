// The walking deploy files as a user runs them (three processes, lockstep,
// MuJoCo): the robot stands in hold, is switched to walking, walks its goal
// forward, turns 90° in place, stops and is switched back to hold. Checked
// from the launch's output: exit code 0, no fall, the steps and the distance
// the plan asked for (within 10 %), the feet's slip and touch-down error, a
// forward speed, the base estimate's drift, and no torque step at either switch. The humanoid
// always; iCub 3 and TALOS when ../shared exists.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "deploy_text.hpp"
#include "progress_lines.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The number after the last `marker` in text; NaN (no comparison holds) without one.
double number_after(const std::string& text, const std::string& marker) {
  return wbi::test::last_value_after(text, marker).value_or(std::nan(""));
}

struct Expected {
  std::string deploy;
  double distance;   // the goal's forward part [m]
  double min_speed;  // over the first speed_distance [m/s]
  double max_drift;  // of the base estimate at the end [mm]
};

// Runs the deploy file and checks its figures; returns the launch's output.
std::string expect_walk(const Expected& expected, std::chrono::seconds timeout) {
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / expected.deploy).string(), "--duration",
       std::to_string(timeout.count() - 10)});
  const auto code = launch.wait(timeout);
  EXPECT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(code.value_or(-1), 0) << out;

  EXPECT_TRUE(contains(out, "falls: 0")) << out;
  EXPECT_EQ(number_after(out, "qp failures: "), 0.0) << out;
  const double planned_steps = number_after(out, "steps walked of ");
  EXPECT_GE(planned_steps, 4.0) << out;
  EXPECT_EQ(number_after(out, "steps: "), planned_steps) << out;
  const double walked = number_after(out, "walked: ");
  EXPECT_NEAR(walked, expected.distance, 0.1 * expected.distance) << out;
  EXPECT_GE(number_after(out, "forward speed over the first "), 0.0) << out;
  const auto speed_at = out.rfind("forward speed over the first ");
  const auto colon = out.find(": ", speed_at);
  EXPECT_GE(std::stod(out.substr(colon + 2)), expected.min_speed) << out;
  EXPECT_LT(number_after(out, "largest stance foot slip: "), 0.01) << out;
  EXPECT_LT(number_after(out, "largest touch-down position error: "), 0.02) << out;
  // The legged base estimate (IMU, the feet's F/T sensors and kinematics) against the truth.
  EXPECT_LT(number_after(out, "horizontal drift at the end "), expected.max_drift) << "mm\n" << out;

  // Hold → walking (its planner with it) and back, each without a torque step.
  const std::regex switch_line(
      R"(switch: ([\w, ]+) → ([\w, ]+) at t = [0-9.]+ s; torque step ([0-9.]+) %)");
  int switches = 0;
  for (std::sregex_iterator it(out.begin(), out.end(), switch_line), end; it != end; ++it) {
    ++switches;
    EXPECT_LT(std::stod((*it)[3].str()), 5.0) << it->str();
  }
  EXPECT_EQ(switches, 2) << out;
  return out;
}

TEST(WalkLaunch, TheHumanoidWalksOneMetreTurnsAndStops) {
  expect_walk({.deploy = "walk.yaml", .distance = 1.0, .min_speed = 0.15, .max_drift = 10.0}, 120s);
}

TEST(WalkLaunch, Icub3WalksTwoMetresAtThreeTenthsOfAMetrePerSecond) {
  if (!wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  expect_walk({.deploy = "icub3_walk.yaml", .distance = 2.0, .min_speed = 0.3, .max_drift = 10.0},
              180s);
}

TEST(WalkLaunch, TalosWalksTwoMetresWithTheSameCode) {
  if (!wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  expect_walk({.deploy = "talos_walk.yaml", .distance = 2.0, .min_speed = 0.2, .max_drift = 40.0},
              180s);
}

// iCub 3 walking at its 0.32 m/s is pushed sideways at the chest, 100 N for
// 0.05 s, in the middle of a single support (the left foot's, t = 5.065 s):
// once toward the stance foot's side, once toward the swinging foot's. It
// catches itself by stepping (step_adjustment_gain) and walks on.
TEST(WalkLaunch, Icub3SurvivesALateralPushMidStrideEitherWay) {
  if (!wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  for (const char* force : {"100", "-100"}) {
    std::string text = wbi::test::deploy_text("icub3_walk.yaml");
    ASSERT_EQ(
        wbi::test::replace_all(text, "lockstep_controllers: [walker]}",
                               std::string("lockstep_controllers: [walker], push_link: "
                                           "chest, push_force: [0, ") +
                                   force + ", 0], push_start_s: 5.065, push_duration_s: 0.05}"),
        1);
    const auto deploy = wbi::test::write_test_file(
        std::string("icub3_walk_push") + (force[0] == '-' ? "_right" : "_left") + ".yaml", text);
    wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                                   {"launch", deploy.string(), "--duration", "170"});
    const auto code = launch.wait(180s);
    ASSERT_TRUE(code.has_value()) << launch.output();
    const std::string out = launch.output();
    EXPECT_EQ(*code, 0) << "push " << force << " N\n" << out;
    EXPECT_TRUE(contains(out, "push")) << "no push reported\n" << out;
    EXPECT_TRUE(contains(out, "falls: 0")) << "push " << force << " N\n" << out;
    EXPECT_NEAR(number_after(out, "walked: "), 2.0, 0.2) << out;
  }
}

struct Outcome {
  int code = -1;
  std::string output;
};

Outcome wbi_command(std::vector<std::string> args) {
  args.insert(args.end(), {"--robot", "humanoid"});
  wbi::test::ChildProcess command(wbi::test::binary_dir() / "bin" / "wbi", args);
  const auto code = command.wait(30s);
  return {code.value_or(-1), command.output()};
}

int count_lines_with(const std::string& text, const std::string& part) {
  int count = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) {
    ++count;
  }
  return count;
}

// Two goals it cannot do, sent while the humanoid walks: one out of range
// (refused by the host), one while walking (refused by the planner). Each is
// refused with one line; the walk goes on as planned and ends standing.
TEST(WalkLaunch, RefusedGoalsLeaveTheHumanoidWalkingItsPlan) {
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / "walk.yaml").string(), "--duration", "110"});
  ASSERT_TRUE(launch.wait_for_output("planned at t =", 60s)) << launch.output();

  const auto out_of_range = wbi_command({"param", "set", "planner", "goal", "1000", "0", "0"});
  EXPECT_EQ(out_of_range.code, 1) << out_of_range.output;
  EXPECT_TRUE(contains(out_of_range.output, "refused: planner: goal")) << out_of_range.output;
  const auto while_walking = wbi_command({"param", "set", "planner", "goal", "0.5", "0", "0"});
  EXPECT_EQ(while_walking.code, 0) << while_walking.output;  // the host takes it; the planner not

  const auto code = launch.wait(120s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  EXPECT_EQ(count_lines_with(out, "walking_planner: goal refused:"), 1) << out;
  EXPECT_TRUE(contains(out, "1 goals refused")) << out;
  EXPECT_TRUE(contains(out, "falls: 0")) << out;
  EXPECT_NEAR(number_after(out, "walked: "), 1.0, 0.1) << out;
}

}  // namespace
