// `wbi launch deploy/icub3_balance.yaml`, `icub3_balance_legs.yaml` and
// `talos_balance.yaml`: the paper's momentum-based balancing, one controller,
// on two real robots' models in MuJoCo (three processes in lockstep, the base
// estimated from the IMU and the legs). The CoM follows a lateral sinusoid
// (3 cm on iCub 3, 4 cm on TALOS, 0.2 Hz) for 20 s, with a push on the torso at
// t = 10 s (40 N / 80 N for 0.1 s). Asserted: com tracking rms < 6 mm (the
// controller's line; about 4 times what the runs give, the issue asked 1 cm),
// and, the bounds, from the simulator's ground truth (sim_robot's
// summary): the feet slip ≤ 2 mm, no joint at a limit for more than 1 % of the
// ticks, every torque within its effort limit. The lockstep runs give, the
// same in 3 runs each (2026-12-02): rms 1.608, 1.845 and 1.393 mm, slip 0.507,
// 0.598 and 0.988 mm, at a limit 0, 0 and 0.64 % (icub3_balance,
// icub3_balance_legs, talos_balance). On icub3_balance.yaml
// the estimator estimates the joint torques from iCub 3's 8 F/T sensors (it has
// no joint-torque sensor): within 20 % RMS of the applied torques of the ground
// truth (10 % measured; estimation/wrenches/README.md).
#include <gtest/gtest.h>

#include <chrono>
#include <iostream>
#include <optional>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "progress_lines.hpp"
#include "real_robot_launch.hpp"
#include "torque_comparison.hpp"

namespace {

using namespace std::chrono_literals;

class RealRobotBalanceLaunch : public testing::TestWithParam<std::string> {};

TEST_P(RealRobotBalanceLaunch, TracksTheSinusoidThroughThePushWithoutSlipOrLimits) {
  if (const std::string skip = wbi::test::real_robot_skip_reason(); !skip.empty()) {
    GTEST_SKIP() << skip;
  }
  // icub3_balance.yaml: estimated torques (state) against applied ones (ground truth).
  const bool estimates_torques = GetParam() == "icub3_balance.yaml";
  wbi::test::TorqueComparison torques;
  std::optional<wbi::dds::Participant> participant;
  std::optional<wbi::dds::Subscriber<wbi::msg::GroundTruth>> truth;
  std::optional<wbi::dds::Subscriber<wbi::msg::StateEstimate>> state;
  if (estimates_torques) {
    participant.emplace("balance_launch_torques");
    truth.emplace(*participant, wbi::dds::topics::ground_truth("icub3"), wbi::dds::qos::kStream,
                  [&](const wbi::msg::GroundTruth& t, const wbi::dds::detail::SampleInfo&) {
                    torques.truth(t.header().stamp_ns(), t.applied_torque());
                  });
    state.emplace(*participant, wbi::dds::topics::state("icub3"), wbi::dds::qos::kStream,
                  [&](const wbi::msg::StateEstimate& e, const wbi::dds::detail::SampleInfo&) {
                    torques.estimated(e.header().stamp_ns(), e.tau(), e.external_wrenches().size());
                  });
  }
  // The controller ends the run after 21 s of robot time (exit_after_s).
  auto launch = wbi::test::launch_deploy_file(GetParam(), 250);
  const auto code = launch.wait(270s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  const auto times = wbi::test::progress_times(out);
  ASSERT_FALSE(times.empty()) << out;
  EXPECT_GE(times.back(), 20.0) << "the run ended early\n" << out;
  EXPECT_NE(out.find("[controller] qp failures: 0\n"), std::string::npos) << out;

  const auto rms = wbi::test::last_value_after(out, "\ncom tracking rms: ");
  const auto slip = wbi::test::last_value_after(out, "': contact slip: ");
  const auto at_limit = wbi::test::last_value_after(out, "': joint at a limit: ");
  const auto effort = wbi::test::last_value_after(out, "': torque: ");
  ASSERT_TRUE(rms && slip && at_limit && effort) << "a summary line is missing\n" << out;
  EXPECT_LT(*rms, 0.006) << out;
  EXPECT_LE(*slip, 2.0) << "mm\n" << out;
  EXPECT_LE(*at_limit, 1.0) << "% of ticks\n" << out;
  EXPECT_LE(*effort, 1.0) << "of the effort limit\n" << out;
  std::cout << GetParam() << ": com tracking rms " << *rms << " m, slip " << *slip
            << " mm, joint at a limit " << *at_limit << " % of ticks\n";
  if (estimates_torques) {
    const auto figures = torques.figures();
    EXPECT_GE(figures.matched, 5000u) << "estimates matched with a ground truth of their stamp";
    EXPECT_EQ(figures.external_wrenches, 9u) << "4 sole plates, 2 lower legs, 2 hands, chest";
    EXPECT_LT(figures.rmse, 0.2 * figures.rms) << figures.rmse << " N·m RMSE, RMS " << figures.rms;
    std::cout << "estimated joint torques: RMSE " << figures.rmse << " N·m, "
              << 100.0 * figures.rmse / figures.rms << " % of the RMS applied torque "
              << figures.rms << " N·m, " << figures.matched << " estimates\n";
  }
}

INSTANTIATE_TEST_SUITE_P(Deploys, RealRobotBalanceLaunch,
                         testing::Values("icub3_balance.yaml", "icub3_balance_legs.yaml",
                                         "talos_balance.yaml"));

}  // namespace
