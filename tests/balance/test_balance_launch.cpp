// The balancing demo as a user runs it: `wbi launch deploy/balance.yaml` starts
// the simulated humanoid, the estimator and the momentum-based balancing
// controller as three processes in lockstep; the CoM follows the lateral
// sinusoid for 20 s and the launch ends with "com tracking rms: X m". The
// controller's signals (wbi/humanoid/signals/balance) reach this process: named,
// one per tick, the CoM reference swinging by the sinusoid's ±5 cm. The
// estimator estimates the joint torques from the two foot F/T sensors
// (joint_torques: force_torque) while the robot also senses them: the two
// agree within 20 % RMS (12 % measured; estimation/wrenches/README.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <mutex>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "child_process.hpp"
#include "progress_lines.hpp"
#include "test_support.hpp"
#include "torque_comparison.hpp"

namespace {

using namespace std::chrono_literals;

TEST(BalanceLaunch, ThreeProcessesTrackTheSinusoidFor20Seconds) {
  // The controller's signals, as a recorder would see them.
  std::mutex mutex;
  std::size_t signals = 0;
  std::vector<std::string> names;
  double ref_y_min = 0.0, ref_y_max = 0.0;
  wbi::dds::Participant participant("balance_launch_signals");
  wbi::dds::Subscriber<wbi::msg::Signals> subscriber(
      participant, wbi::dds::topics::signals("humanoid", "balance"), wbi::dds::qos::kStream,
      [&](const wbi::msg::Signals& s, const wbi::dds::detail::SampleInfo&) {
        std::lock_guard lock(mutex);
        if (signals++ == 0) {
          for (const auto& name : s.names()) {
            names.emplace_back(name.to_string());
          }
        }
        if (s.values().size() > 4) {
          ref_y_min = std::min(ref_y_min, s.values()[4]);
          ref_y_max = std::max(ref_y_max, s.values()[4]);
        }
      });

  // Estimated joint torques (state) against sensed ones (sensor samples), matched by
  // source stamp, after 1.5 s of settling.
  wbi::test::TorqueComparison torques;
  wbi::dds::Subscriber<wbi::msg::SensorSample> sensors(
      participant, wbi::dds::topics::sensors("humanoid"), wbi::dds::qos::kStream,
      [&](const wbi::msg::SensorSample& sample, const wbi::dds::detail::SampleInfo&) {
        torques.truth(sample.header().stamp_ns(), sample.joint_torque());
      });
  wbi::dds::Subscriber<wbi::msg::StateEstimate> state(
      participant, wbi::dds::topics::state("humanoid"), wbi::dds::qos::kStream,
      [&](const wbi::msg::StateEstimate& estimate, const wbi::dds::detail::SampleInfo&) {
        torques.estimated(estimate.header().stamp_ns(), estimate.tau(),
                          estimate.external_wrenches().size());
      });

  // The controller ends the run after 21 s of robot time (exit_after_s); --duration
  // is only a safety net.
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / "balance.yaml").string(), "--duration",
       "150"});
  const auto code = launch.wait(170s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  const auto times = wbi::test::progress_times(out);
  ASSERT_GE(times.size(), 10u) << "no progress lines\n" << out;
  EXPECT_GE(times.back(), 20.0) << "the run ended early\n" << out;
  EXPECT_NE(out.find("[controller] qp failures: 0\n"), std::string::npos) << out;
  // Where a tick went: the robot's lockstep line, the estimator's and the
  // balancer's own times (deploy/README.md, "Where a tick goes").
  EXPECT_NE(out.find("lockstep: simulated "), std::string::npos) << out;
  EXPECT_NE(out.find("[estimator] estimator of robot 'humanoid': "), std::string::npos) << out;
  EXPECT_NE(out.find("[controller] balance: "), std::string::npos) << out;
  EXPECT_NE(out.find(" cycles, read + update + write mean "), std::string::npos) << out;
  // Event-driven (wait_for_state): one balancer cycle per state, so one per
  // tick; the robot steps a tick or two more while the controller's process ends.
  const auto number_after = [&](const std::string& key) {
    const auto found = out.find(key);
    return found == std::string::npos ? -1L : std::stol(out.substr(found + key.size()));
  };
  const long cycles = number_after("[controller] balance: ");
  const long ticks = number_after("ground truth over ");
  EXPECT_GT(ticks, 20000) << out;
  EXPECT_LE(cycles, ticks) << "more balancer cycles than ticks\n" << out;
  EXPECT_GE(cycles, ticks - 3) << out;
  // ... each on the DDS thread that delivered its state (controllers/README.md,
  // "Which thread") but the first, which the runner's loop thread answers,
  // and any state no arrival answered for ten periods: its generator's point
  // was that late (0 alone, 1-2 with the suite beside it at -j2). 0.1 %.
  const auto line_at = out.find("[controller] balance: ");
  const std::string line = out.substr(line_at, out.find('\n', line_at) - line_at);
  const auto count_at = line.find("; ");
  ASSERT_NE(count_at, std::string::npos) << line;
  EXPECT_NE(line.find(" on their event's thread", count_at), std::string::npos) << line;
  EXPECT_GE(std::stol(line.substr(count_at + 2)), cycles - 21) << line;
  const std::string marker = "\ncom tracking rms: ";
  const auto at = out.rfind(marker);
  ASSERT_NE(at, std::string::npos) << out;
  const auto end = out.find(" m", at + 1);
  ASSERT_EQ(out.find('\n', end), out.size() - 1) << "the rms is not the last line:\n" << out;
  // Lockstep: the run gives 1.281 mm (2026-12-02, the same in 3 runs); 5 mm
  // is about 4 times that (the issue asked 1 cm).
  const double com_rms = std::stod(out.substr(at + marker.size()));
  EXPECT_LT(com_rms, 0.005) << out;
  std::cout << "com tracking rms " << com_rms << " m\n";

  std::lock_guard lock(mutex);
  EXPECT_GE(signals, 10000u) << "one sample per tick over 21 s (a reliable stream may skip some)";
  ASSERT_GE(names.size(), 5u);
  EXPECT_EQ(names[1], "com_y");
  EXPECT_EQ(names[4], "com_ref_y");
  EXPECT_NEAR(ref_y_max - ref_y_min, 0.10, 0.005) << "the reference's swing, 2 × 5 cm";

  const auto figures = torques.figures();
  EXPECT_GE(figures.matched, 5000u) << "estimates matched with a sensor sample of their stamp";
  EXPECT_EQ(figures.external_wrenches, 3u) << "l_foot, r_foot, chest";
  EXPECT_LT(figures.rmse, 0.2 * figures.rms) << figures.rmse << " N·m RMSE, RMS " << figures.rms;
  std::cout << "estimated joint torques: RMSE " << figures.rmse << " N·m, "
            << 100.0 * figures.rmse / figures.rms << " % of the RMS torque " << figures.rms
            << " N·m, " << figures.matched << " estimates\n";
}

}  // namespace
