// The built-in `hold` keeps the project's humanoid standing (issue 36): the
// humanoid of deploy/balance.yaml (every joint torque-controlled, the base
// from the IMU and both feet), simulated in lockstep in this process, with a
// controller host over real DDS whose only active controller is hold on the
// soles. The ground truth shows whether the CoM drifted, the feet stayed
// loaded and the torques stayed smooth.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>

#include <wbi/controllers/controller_host.hpp>
#include <wbi/controllers/momentum_balance_controller.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/model/algorithms.hpp>
#include <wbi/model/com.hpp>
#include <wbi/sim_rig/humanoid_joints.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

#include "allocation_counter.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::controllers::ControllerHost;

const std::vector<std::string> kJoints = wbi::sim_rig::humanoid_joints();
constexpr double kPeriod = 0.001;  // the simulation's tick
// The robot is placed on the ground at t = 0 and lands in its contact springs
// (1.4 mm) within the first tenths of a second; measured from then on.
constexpr double kLanded = 0.5;

// deploy/robots/humanoid.yaml with the URDF path made absolute, and `extra` appended.
std::string sim_config(const std::string& robot) {
  std::ifstream in(wbi::test::source_dir() / "deploy" / "robots" / "humanoid.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string relative = "../../models/humanoid.urdf";
  text.replace(text.find(relative), relative.size(),
               wbi::test::project_model("humanoid.urdf").string());
  const auto path = std::filesystem::temp_directory_path() /
                    ("wbi_hold_" + robot + "_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

struct HoldRun {
  double com_drift = 0.0;         // largest horizontal distance of the true CoM from its start [m]
  double com_sink = 0.0;          // largest drop of the true CoM [m]
  double max_joint_error = 0.0;   // largest |q − q at activation| after the first second [rad]
  double max_torque_step = 0.0;   // largest |τ_i(k) − τ_i(k−1)| [N m]
  double max_torque = 0.0;        // largest |τ_i| [N m]
  double min_normal_force = 1e9;  // smallest normal force on a foot [N]
  double max_foot_slip = 0.0;     // horizontal sole displacement [m]
  std::string active;             // the host's active controller at the end
  long allocations = 0;           // of hold's ticks, over the last 100
};

// `seconds` of lockstep: hold from the first tick, or the balancer (its
// lateral sinusoid, 5 cm at 0.2 Hz) switched to hold at `balance_s`.
// Measured from kLanded after hold took over. bandwidth_hz < 0: hold's default.
HoldRun run_hold(const std::string& robot, double seconds, const std::string& engine,
                 double balance_s = 0.0, double bandwidth_hz = -1.0) {
  const auto urdf = wbi::test::project_model("humanoid.urdf").string();
  const std::string config = sim_config(robot);
  wbi::sim_rig::InProcessRobot rig(
      "hold_test",
      "robot: " + robot + "\nconfig: " + config + "\nengine: " + engine +
          "\nlockstep: true\nlockstep_controllers: [host]\n",
      "robot: " + robot + "\nbase: legged\nurdf: " + urdf +
          "\nfoot_force_torque: [l_foot_ft, r_foot_ft]\nmethod: backward-difference\ncutoff: 50\n");
  std::filesystem::remove(config);  // read when the rig configured the sim
  wbi::dds::Subscriber<wbi::msg::GroundTruth> truth(
      rig.participant(), wbi::dds::topics::ground_truth(robot), wbi::dds::qos::kStream);

  wbi::DdsInterfaceOptions options;
  options.robot = robot;
  options.controller = "host";
  options.urdf = urdf;
  options.max_age_s = 5.0;  // lockstep: time is the simulation's
  auto humanoid = wbi::make_dds_interface(options);
  humanoid->add_joints(kJoints);
  rig.start_simulation();
  humanoid->init(20s);

  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  ControllerHost host(*humanoid, report, events, ControllerHost::Options{});
  auto& hold = host.add("hold", "hold", wbi::controllers::make_hold_controller());
  if (bandwidth_hz > 0.0) {
    hold.set(hold.index("bandwidth_hz"), std::vector<double>{bandwidth_hz});
  }
  bandwidth_hz = hold.snapshot(hold.index("bandwidth_hz"))[0];
  hold.set_text(hold.index("contacts"), "l_sole,r_sole");
  host.configure("hold");
  if (balance_s > 0.0) {
    host.add("balance", "momentum_balance",
             std::make_unique<wbi::controllers::MomentumBalanceController>());
    host.configure("balance");
    host.set_initial("balance");
  } else {
    host.set_initial("hold");
  }
  const int switch_tick = static_cast<int>(std::lround(balance_s / kPeriod));

  const auto model = wbi::model::load_urdf_file(urdf);
  wbi::model::Data data(model);
  const int soles[2] = {model.frame_id("l_sole"), model.frame_id("r_sole")};
  Eigen::Vector3d com_start = Eigen::Vector3d::Zero();
  Eigen::Vector3d sole_start[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  bool have_start = false;
  Eigen::VectorXd q_model(model.nq), q_start, tau_last;
  wbi::RobotState state(humanoid->dofs());
  wbi::dds::Received<wbi::msg::GroundTruth> gt;
  HoldRun run;
  const int ticks = static_cast<int>(seconds / kPeriod);
  for (int k = 0; k < ticks; ++k) {
    // The first tick answers the estimate init() read; each later one the next.
    humanoid->state().read_robot_state(state,
                                       k == 0 ? wbi::ReadMode::latest : wbi::ReadMode::blocking);
    if (balance_s > 0.0 && k == switch_tick) {
      EXPECT_EQ(host.schedule_switch("hold"), "");
    }
    const long before = wbi::test::thread_allocation_count();
    host.tick(k * kPeriod, kPeriod);
    const Eigen::VectorXd& tau = host.last_command();
    if (k >= ticks - 100) {
      // The last 100 ticks' allocations, less those of as many bare writes of
      // the same command (Fast DDS allocates in a reliable write; see
      // test_controller_host): hold's own.
      const long after_tick = wbi::test::thread_allocation_count();
      humanoid->set_control_reference(tau);
      run.allocations +=
          (after_tick - before) - (wbi::test::thread_allocation_count() - after_tick);
    }
    const bool landed = (k - switch_tick) * kPeriod >= kLanded;
    if (k == switch_tick) {
      q_start = state.q;  // the posture hold took over
    }
    if (landed) {
      run.max_torque_step = std::max(run.max_torque_step, (tau - tau_last).cwiseAbs().maxCoeff());
      run.max_torque = std::max(run.max_torque, tau.cwiseAbs().maxCoeff());
      run.max_joint_error =
          std::max(run.max_joint_error, (state.q - q_start).cwiseAbs().maxCoeff());
    }
    tau_last = tau;
    if (!truth.latest_into(gt) || !landed) {
      continue;
    }
    const auto& s = gt.sample;
    const auto& p = s.base_pose();
    q_model.head<3>() << p.position().x(), p.position().y(), p.position().z();
    q_model.segment<4>(3) << p.orientation().w(), p.orientation().x(), p.orientation().y(),
        p.orientation().z();
    q_model.tail(model.n_joints) = Eigen::Map<const Eigen::VectorXd>(s.q().data(), model.n_joints);
    const Eigen::Vector3d com = wbi::model::center_of_mass(model, data, q_model);
    wbi::model::forward_kinematics(model, data, q_model);
    Eigen::Vector3d sole[2];
    for (int foot = 0; foot < 2; ++foot) {
      sole[foot] = wbi::model::frame_pose(model, data, soles[foot]).block<3, 1>(0, 3);
    }
    if (!have_start) {
      have_start = true;
      com_start = com;
      sole_start[0] = sole[0];
      sole_start[1] = sole[1];
    }
    run.com_drift = std::max(run.com_drift, (com - com_start).head<2>().norm());
    run.com_sink = std::max(run.com_sink, com_start.z() - com.z());
    for (int foot = 0; foot < 2; ++foot) {
      run.max_foot_slip =
          std::max(run.max_foot_slip, (sole[foot] - sole_start[foot]).head<2>().norm());
    }
    for (const auto& w : s.contact_wrenches()) {
      run.min_normal_force = std::min(run.min_normal_force, w.force().z());
    }
  }
  run.active = host.active();
  rig.sim().shutdown();
  rig.estimator().shutdown();
  std::printf(
      "%s, %g Hz%s: CoM drift %.2f mm, sink %.2f mm; joint error %.4f rad; torque: largest %.1f N "
      "m, "
      "largest tick-to-tick change %.2f N m; min foot f_z %.1f N; slip %.2f mm (from t = %.1f s)\n",
      engine.c_str(), bandwidth_hz, balance_s > 0.0 ? ", after the balancer" : "",
      1e3 * run.com_drift, 1e3 * run.com_sink, run.max_joint_error, run.max_torque,
      run.max_torque_step, run.min_normal_force, 1e3 * run.max_foot_slip, kLanded);
  return run;
}

// The humanoid stood in hold 0.9 mm from where it began, 0.0012 rad from the
// held posture, with 3.3 N m as the largest change between two commands and
// each foot carrying at least 124 N (2026-11-27, both engines). 2026-12-02,
// the same in 3 runs (lockstep): CoM drift 0.37, 0.61 and 0.42 mm, joint error
// 0.0008, 0.0008 and 0.0027 rad, largest change 3.21-3.23 N m, at least
// 114-163 N a foot, sink and slip 0.01 mm or less (wbi, mujoco, wbi after the
// balancer); drift and joint error are bounded at about 3-4 times these. Before, hold
// (gains from the joint block of M) let it fall at every bandwidth: the CoM
// 0.9 m away, both feet off the ground, with 20–540 N m between two commands.
void expect_standing(const HoldRun& run, double min_foot_force = 50.0) {
  EXPECT_EQ(run.active, "hold");
  // The sole is 8 cm wide: 2 mm is a twentieth of its half width, far from an
  // edge; the balancer tracks its CoM within 1 cm.
  EXPECT_LT(run.com_drift, 0.002) << "m";
  EXPECT_LT(run.com_sink, 0.002) << "m";
  EXPECT_LT(run.max_joint_error, 0.008) << "rad";
  // Chattering hold reached 100–770 N m between two ticks; 10 N m is a sixth
  // of the knees' and hips' 60 N m effort limit.
  EXPECT_LT(run.max_torque_step, 10.0) << "N m";
  // 33.75 kg on two feet: 165 N each; each keeps at least a third of it.
  EXPECT_GT(run.min_normal_force, min_foot_force) << "N";
  EXPECT_LT(run.max_foot_slip, 0.001) << "m";
  EXPECT_EQ(run.allocations, 0) << "heap allocations in hold's ticks";
}

// 6 s at hold's default bandwidth (2 Hz), 5.5 s of it measured.
TEST(HoldStand, TheHumanoidStandsInHold) { expect_standing(run_hold("hold_stand", 6.0, "wbi")); }

TEST(HoldStand, TheHumanoidStandsInHoldInMujoco) {
#ifndef WBI_WITH_MUJOCO
  GTEST_SKIP() << "built without MuJoCo (libmujoco-dev)";
#endif
  expect_standing(run_hold("hold_stand_mujoco", 6.0, "mujoco"));
}

// The fallback's case: hold takes over from the balancer at t = 2 s, 1.5 s
// into its sinusoid, the CoM 4.75 cm towards the left foot.
TEST(HoldStand, TheHumanoidStandsInHoldAfterTheBalancer) {
  // The balancer hands over with 279 N and 55 N on the feet (the CoM 4.75 cm
  // towards the left one); the lighter foot keeps at least half of its 55 N.
  expect_standing(run_hold("hold_after_balance", 8.0, "wbi", 2.0), 25.0);
}

}  // namespace
