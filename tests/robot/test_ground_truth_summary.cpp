// sim_robot's end-of-run summary (src/ground_truth_summary.hpp) on given ground
// truths: a foot's horizontal travel from where it started, the share of ticks
// a joint spends within 1 mrad of (or beyond) a limit, the largest torque
// against the effort limit, and the lines a launch test reads.
#include <gtest/gtest.h>

#include <sstream>

#include "ground_truth_summary.hpp"

namespace {

using wbi::actuation::BackendDescription;
using wbi::actuation::GroundTruth;
using wbi::robot::GroundTruthSummary;

// Two joints on a floating base (q: 3 position, 4 quaternion, 2 joints), two feet.
BackendDescription two_joints() {
  BackendDescription d;
  d.robot = "biped";
  d.floating_base = true;
  d.joint_names = {"hip", "knee"};
  d.position_lower = {-1.0, 0.0};
  d.position_upper = {1.0, 2.0};
  d.velocity_limit = {10.0, 10.0};
  d.effort_limit = {100.0, 50.0};
  return d;
}

GroundTruth truth(double hip, double knee, const Eigen::Vector3d& right_foot,
                  double hip_torque = 0.0, double knee_torque = 0.0) {
  GroundTruth t;
  t.q = Eigen::VectorXd::Zero(9);
  t.q[3] = 1.0;
  t.q[7] = hip;
  t.q[8] = knee;
  t.tau_actuator = Eigen::Vector2d(hip_torque, knee_torque);
  t.contact_links = {"l_foot", "r_foot"};
  t.contact_positions = {Eigen::Vector3d(0, 0.1, 0), right_foot};
  return t;
}

TEST(GroundTruthSummary, SlipLimitsAndTorquesOfARun) {
  const Eigen::Vector3d start(0, -0.1, 0);
  GroundTruthSummary summary(two_joints(), truth(0.0, 1.0, start));
  // The right foot slides 3 mm sideways and 4 mm forward (5 mm), then back;
  // its 1 cm of lift does not count. The knee sits at its lower limit for 2 of 4
  // ticks (one within 1 mrad, one beyond); the hip's largest torque is 60 of 100.
  summary.add(truth(0.0, 0.0005, start + Eigen::Vector3d(0.004, 0.003, 0.01), -60.0, 10.0));
  summary.add(truth(0.5, -0.01, start + Eigen::Vector3d(0.001, 0.0, 0.0), 20.0, -25.0));
  summary.add(truth(0.2, 0.5, start, 0.0, 0.0));
  summary.add(truth(0.2, 0.5, start, 0.0, 0.0));
  EXPECT_EQ(summary.ticks(), 4u);
  EXPECT_NEAR(summary.largest_slip(), 0.005, 1e-12);
  EXPECT_EQ(summary.slipping_link(), 1);
  EXPECT_DOUBLE_EQ(summary.largest_limit_fraction(), 0.5);
  EXPECT_EQ(summary.joint_most_at_limit(), 1);
  EXPECT_DOUBLE_EQ(summary.largest_effort_fraction(), 0.6);
  EXPECT_EQ(summary.joint_nearest_effort(), 0);  // the knee's 25 of 50 is 0.5

  std::ostringstream out;
  summary.print(out, "sim_robot 'biped'");
  const std::string text = out.str();
  EXPECT_NE(text.find("sim_robot 'biped': ground truth over 4 ticks\n"), std::string::npos) << text;
  EXPECT_NE(text.find("sim_robot 'biped': contact slip: 5.000 mm (r_foot,"), std::string::npos)
      << text;
  EXPECT_NE(text.find("sim_robot 'biped': joint at a limit: 50.00 % of ticks (knee,"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("sim_robot 'biped': torque: 0.600 of the effort limit (hip: 60.0 of 100.0"),
            std::string::npos)
      << text;
}

// A fixed-base arm: no contact links, so no slip line.
TEST(GroundTruthSummary, WithoutContactsThereIsNoSlipLine) {
  BackendDescription d = two_joints();
  d.floating_base = false;
  GroundTruth t;
  t.q = Eigen::Vector2d(0.0, 1.0);
  t.tau_actuator = Eigen::Vector2d(0.0, 0.0);
  GroundTruthSummary summary(d, t);
  summary.add(t);
  EXPECT_LT(summary.largest_slip(), 0.0);
  std::ostringstream out;
  summary.print(out, "arm");
  EXPECT_EQ(out.str().find("slip"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("arm: joint at a limit: 0.00 % of ticks"), std::string::npos)
      << out.str();
}

}  // namespace
