// The deploy file's push (sim_robot's push_* parameters) is added to the robot
// config's pushes: the humanoid of deploy/robots/humanoid.yaml, pushed sideways
// on its pelvis in the own plant, moves sideways; bad push parameters are one
// line naming the key.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include <wbi/runtime/parameters.hpp>
#include <wbi/sim_robot/engine_registry.hpp>

#include "test_support.hpp"

namespace {

using wbi::runtime::Parameters;

std::unique_ptr<wbi::actuation::SimulationBackend> humanoid_engine(const std::string& push) {
  const auto parameters = Parameters::from_string(push, "component 'sim'");
  const wbi::sim_robot::EngineContext context{
      "humanoid", wbi::test::source_dir() / "deploy" / "robots" / "humanoid.yaml", parameters};
  return wbi::sim_robot::builtin_engines().create("wbi", context);
}

// Base velocity along y after 0.1 s with the joints unpowered (IDLE).
double sideways_velocity(wbi::actuation::SimulationBackend& sim) {
  sim.configure();
  sim.activate();
  for (int k = 0; k < 100; ++k) {
    sim.step();
  }
  return sim.ground_truth().base_velocity[1];
}

TEST(SimRobotPush, TheDeployFilesPushMovesTheRobot) {
  const auto pushed = humanoid_engine(
      "push_link: root_link\npush_force: [0, 300, 0]\npush_start_s: 0\npush_duration_s: 0.05\n");
  const auto still = humanoid_engine("{}");
  const double v_pushed = sideways_velocity(*pushed);
  const double v_still = sideways_velocity(*still);
  // 15 N·s on a ≈ 30 kg robot held by its feet' friction: clearly moving, the
  // unpushed one not.
  EXPECT_GT(v_pushed - v_still, 0.05) << "pushed " << v_pushed << " m/s, not " << v_still;
}

void expect_error(const std::string& push, const std::string& message) {
  try {
    humanoid_engine(push);
    ADD_FAILURE() << "no error for: " << push;
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
  }
}

TEST(SimRobotPush, BadPushParametersNameTheKey) {
  expect_error("push_link: pelvis\npush_force: [0, 1, 0]\npush_start_s: 1\n",
               "push_link: unknown link or frame 'pelvis'");
  expect_error("push_force: [0, 1, 0]\npush_start_s: 1\n", "missing parameter 'push_link'");
  expect_error("push_link: root_link\npush_start_s: 1\n",
               "push_force: missing (a push needs push_link, push_force and push_start_s)");
  expect_error("push_link: root_link\npush_force: [0, 1]\npush_start_s: 1\n",
               "push_force: expected 3 numbers [x, y, z], got 2");
  expect_error("push_link: root_link\npush_force: [0, 1, 0]\npush_start_s: 1\npush_duration_s: 0\n",
               ":4: component 'sim': push_duration_s: must be > 0 [s]");
  expect_error("push_link: root_link\npush_force: [0, 1, 0]\npush_start_s: -1\n",
               ":3: component 'sim': push_start_s: must be >= 0 [s]");
}

}  // namespace
