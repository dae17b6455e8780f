// The engine-neutral plan of a robot config (wbi::sim_models): what every engine
// steps from, checked on the project's humanoid and arm, and the two pieces
// every engine shares at run time (held commands, sensor noise).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <wbi/model/urdf.hpp>
#include <wbi/sim_models/command_hold.hpp>
#include <wbi/sim_models/sensor_noise.hpp>
#include <wbi/sim_models/sim_plan.hpp>

#include "sim_test_common.hpp"

namespace {

using wbi::robot_config::RobotConfig;
using wbi::sim::test::humanoid_config;
using wbi::sim::test::model_path;
namespace sm = wbi::sim_models;

struct Planned {
  RobotConfig config;
  wbi::model::Model model;
  sm::SimPlan plan;
};

Planned plan_of(RobotConfig config) {
  wbi::robot_config::complete_from_urdf(config);
  Planned p{config, {}, {}};
  wbi::model::LoadOptions options;
  options.fixed_base = config.fixed_base;
  p.model = wbi::model::load_urdf_file(config.urdf, options);
  p.plan = sm::make_sim_plan(p.config, p.model, "robot config");
  return p;
}

TEST(SimPlan, HumanoidTablesFollowTheModelAndTheConfig) {
  RobotConfig c = humanoid_config();
  c.initial_joint_positions["l_knee"] = -0.3;
  c.pushes.push_back(
      {"chest", 1.0, 0.25, Eigen::Vector3d(0.0, 40.0, 0.0), Eigen::Vector3d::Zero()});
  const Planned p = plan_of(c);
  const sm::SimPlan& plan = p.plan;
  const wbi::model::Model& m = p.model;

  ASSERT_EQ(plan.n_joints, m.n_joints);
  EXPECT_EQ(plan.nv, m.nv);
  EXPECT_EQ(plan.description.joint_names, m.joint_name);
  for (int j = 0; j < m.n_joints; ++j) {
    EXPECT_EQ(plan.effort_limit[j], m.joint_effort_limit[static_cast<std::size_t>(j)]);
  }
  // The initial state: the config's base pose and joint, before any placing on the ground.
  ASSERT_EQ(plan.q0.size(), m.nq);
  EXPECT_DOUBLE_EQ(plan.q0[2], 0.555);
  EXPECT_DOUBLE_EQ(plan.q0[3], 1.0);  // identity orientation, w first
  EXPECT_DOUBLE_EQ(plan.q0[m.base_nq + m.joint_id("l_knee")], -0.3);

  // Contacts: the floating humanoid has them (auto), one link per foot box.
  EXPECT_TRUE(plan.contacts_on);
  EXPECT_EQ(plan.contact_links, (std::vector<std::string>{"l_foot", "r_foot"}));
  ASSERT_EQ(plan.contact_link_frames.size(), 2U);
  EXPECT_EQ(plan.contact_link_frames[1], m.frame_id("r_foot"));
  EXPECT_EQ(plan.contact_link_of.size(), p.config.contacts.size());

  ASSERT_EQ(plan.pushes.size(), 1U);
  EXPECT_EQ(plan.pushes[0].frame, m.frame_id("chest"));
  EXPECT_DOUBLE_EQ(plan.pushes[0].start, 1.0);
  EXPECT_DOUBLE_EQ(plan.pushes[0].end, 1.25);
  // A push is active on steps [round(start / h), round(end / h)).
  EXPECT_EQ(sm::step_index(plan.pushes[0].end, 5e-4), 2500);

  // Sensors: the F/T frame is the fixed joint's child link.
  ASSERT_EQ(plan.force_torque.size(), 2U);
  EXPECT_EQ(plan.force_torque[0].child_link, "l_foot");
  EXPECT_EQ(plan.force_torque[0].frame, m.frame_id("l_foot"));
  EXPECT_EQ(plan.description.ft_frames, (std::vector<std::string>{"l_foot", "r_foot"}));
  ASSERT_EQ(plan.imus.size(), 1U);
  EXPECT_EQ(plan.imus[0].frame, m.frame_id("imu_frame"));
  EXPECT_EQ(plan.description.imu_names, (std::vector<std::string>{"imu"}));

  // The ground truth's layout.
  const wbi::actuation::GroundTruth truth = plan.initial_ground_truth();
  EXPECT_EQ(truth.q, plan.q0);
  EXPECT_EQ(truth.nu.size(), m.nv);
  EXPECT_EQ(truth.tau.size(), m.n_joints);
  EXPECT_EQ(truth.contact_links, plan.contact_links);
  EXPECT_EQ(truth.contact_wrenches.size(), 2U);
}

TEST(SimPlan, AFixedBaseArmHasNoContactsByDefault) {
  RobotConfig c;
  c.urdf = model_path("arm7.urdf");
  c.fixed_base = true;
  const Planned p = plan_of(c);
  EXPECT_FALSE(p.plan.contacts_on);
  EXPECT_TRUE(p.plan.contact_links.empty());
  EXPECT_EQ(p.plan.q0.size(), p.model.nq);
  EXPECT_EQ(p.plan.nv, 7);
}

TEST(SimPlan, BadNamesAreErrorsThatNameTheItem) {
  auto expect_error = [](RobotConfig c, const std::string& part) {
    try {
      plan_of(std::move(c));
      ADD_FAILURE() << "no error for " << part;
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
    }
  };
  RobotConfig c = humanoid_config();
  c.imus[0].frame = "imu_fram";
  expect_error(c, "robot config: imus 'imu': unknown link or frame 'imu_fram'");
  c = humanoid_config();
  c.force_torque[0].joint = "l_knee";
  expect_error(c, "force_torque 'l_foot_ft': joint 'l_knee' is not a fixed joint");
  c = humanoid_config();
  c.force_torque[1].joint = "r_foot_ft";
  expect_error(c, "force_torque 'r_foot_ft': unknown joint 'r_foot_ft'");
  c = humanoid_config();
  c.pushes.push_back({"chest", 0.0, -0.1, Eigen::Vector3d::UnitX(), Eigen::Vector3d::Zero()});
  expect_error(c, "pushes: 'duration' must be >= 0");
  c = humanoid_config();
  c.initial_base_orientation.setZero();
  expect_error(c, "'initial_base_orientation' must be non-zero");
  c = humanoid_config();
  c.initial_joint_positions["l_kne"] = 0.1;
  expect_error(c, "initial_joint_positions: unknown joint 'l_kne'");
}

TEST(CommandHold, HoldsTheCommandsUntilReleased) {
  const Planned p = plan_of(humanoid_config());
  sm::CommandHold hold(p.plan);
  wbi::actuation::JointCommands commands;
  commands.resize(p.plan.n_joints);
  commands.mode[0] = wbi::actuation::OutputMode::kTorque;
  commands.value[0] = 1e6;  // saturated at the effort limit
  commands.mode[1] = wbi::actuation::OutputMode::kTorque;
  commands.value[1] = 2.5;
  hold.hold(commands);
  EXPECT_DOUBLE_EQ(hold.actuate(0, 0.0), p.plan.effort_limit[0]);
  EXPECT_DOUBLE_EQ(hold.actuate(1, 0.3), 2.5);
  EXPECT_DOUBLE_EQ(hold.torque()[1], 2.5);
  hold.release();
  EXPECT_DOUBLE_EQ(hold.actuate(1, 0.3), 0.0);
  EXPECT_DOUBLE_EQ(hold.pwm()[1], p.plan.motors[1].duty(0.0, 0.3));
}

TEST(SensorNoise, SameSeedSameReadingsAndPositionsQuantised) {
  RobotConfig c = humanoid_config();
  c.wbi.encoders.position_noise = 1e-3;
  c.wbi.encoders.velocity_noise = 1e-2;
  c.imus[0].gyro_noise = 1e-2;
  c.force_torque[0].force_noise = 0.5;
  const Planned p = plan_of(c);
  auto readings = [&](std::uint64_t seed) {
    RobotConfig seeded = p.config;
    seeded.wbi.seed = seed;
    sm::SensorNoise noise(seeded);
    wbi::actuation::SensorReadings r;
    r.resize(p.plan.description);
    r.position.setConstant(0.1);
    noise.apply(r, wbi::actuation::Time(42));
    return r;
  };
  const auto a = readings(7), b = readings(7), other = readings(8);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.force_torque[0].wrench, b.force_torque[0].wrench);
  EXPECT_NE(a.velocity, other.velocity);
  EXPECT_EQ(a.joint_stamp, wbi::actuation::Time(42));
  EXPECT_EQ(a.imus[0].stamp, wbi::actuation::Time(42));
  const double step = sm::encoder_step(c.wbi.encoders);
  for (Eigen::Index j = 0; j < a.position.size(); ++j) {
    EXPECT_NEAR(a.position[j] / step, std::round(a.position[j] / step), 1e-9);
  }
  EXPECT_EQ(a.force_torque[1].wrench, wbi::actuation::Vector6d::Zero().eval());  // no noise given
  EXPECT_NE(a.imus[0].gyro, Eigen::Vector3d::Zero().eval());
  EXPECT_EQ(a.imus[0].accel, Eigen::Vector3d::Zero().eval());
}

}  // namespace
