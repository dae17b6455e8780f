// WalkingPlan (controllers/walking): the DCM and its velocity continuous
// across every phase, the LIPM in single support, the CoM it implies, swing
// feet and contact weights, walk_to's steps and refusals, and sample()
// allocating nothing. Phase boundaries are computed here from the
// parameters, as walking_plan.hpp documents them.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <wbi/controllers/walking_plan.hpp>
#include <wbi/types.hpp>

#include "allocation_counter.hpp"

namespace {

using wbi::controllers::walking::Foot;
using wbi::controllers::walking::FootPose;
using wbi::controllers::walking::Footstep;
using wbi::controllers::walking::WalkingParameters;
using wbi::controllers::walking::WalkingPlan;
using wbi::controllers::walking::WalkingReference;

constexpr double kPi = std::numbers::pi;

// Standing at t = 0 on flat ground, feet at step_width, CoM above their middle.
WalkingPlan standing(const WalkingParameters& p, double sole_z = 0.0) {
  WalkingPlan plan(p);
  const double half = 0.5 * p.step_width;
  plan.stand(0.0, {Eigen::Vector3d(0.1, 0.2 + half, sole_z), 0.0},
             {Eigen::Vector3d(0.1, 0.2 - half, sole_z), 0.0},
             Eigen::Vector3d(0.1, 0.2, sole_z + p.com_height));
  return plan;
}

WalkingReference at(const WalkingPlan& plan, double t) {
  WalkingReference r;
  plan.sample(t, r);
  return r;
}

// Begin of every phase (first double support, then single and double support
// per step) and end_time() last.
std::vector<double> boundaries(const WalkingPlan& plan, double t0) {
  const WalkingParameters& p = plan.parameters();
  std::vector<double> b{t0, t0 + p.final_double_support_s};
  const std::size_t n = plan.footsteps().size();
  for (std::size_t i = 0; i < n; ++i) {
    b.push_back(b.back() + p.single_support_s);
    b.push_back(b.back() + (i + 1 == n ? p.final_double_support_s : p.double_support_s));
  }
  return b;
}

// The largest |v| over the walk, sampled every 1 ms.
double largest(const WalkingPlan& plan, int from, int size,
               Eigen::Matrix<double, 16, 1> WalkingReference::*field) {
  double most = 0.0;
  for (double t = 0.0; t <= plan.end_time() + 1.0; t += 1e-3) {
    most = std::max(most, (at(plan, t).*field).segment(from, size).norm());
  }
  return most;
}

Eigen::Vector3d dcm(const WalkingReference& r) { return r.position.segment<3>(0); }
Eigen::Vector3d com(const WalkingReference& r) { return r.position.segment<3>(3); }
Eigen::Vector4d sole(const WalkingReference& r, Foot foot) {
  return r.position.segment<4>(6 + 4 * static_cast<int>(foot));
}
double weight(const WalkingReference& r, Foot foot) {
  return r.position[14 + static_cast<int>(foot)];
}

class TwoMetresAndATurn : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(plan.walk_to(0.0, 2.0, 0.0, kPi / 2), ""); }
  WalkingParameters p;
  WalkingPlan plan = standing(p);
};

TEST_F(TwoMetresAndATurn, DcmAndItsVelocityContinuousAtEveryPhaseBoundary) {
  const double h = 1e-6;
  const double speed = largest(plan, 0, 3, &WalkingReference::velocity);
  const double acceleration = largest(plan, 0, 3, &WalkingReference::acceleration);
  ASSERT_GT(speed, 0.05);
  for (const double b : boundaries(plan, 0.0)) {
    const WalkingReference before = at(plan, b - h), after = at(plan, b + h);
    EXPECT_LE((dcm(after) - dcm(before)).norm(), 1.5 * 2 * h * speed) << "at t = " << b;
    EXPECT_LE((after.velocity.head<3>() - before.velocity.head<3>()).norm(),
              1.5 * 2 * h * acceleration)
        << "at t = " << b;
  }
}

TEST_F(TwoMetresAndATurn, SingleSupportDcmDivergesFromTheStanceFoot) {
  const double w = plan.omega(), h = 1e-5;
  const auto b = boundaries(plan, 0.0);
  for (std::size_t i = 0; i < plan.footsteps().size(); ++i) {
    const Foot stance = plan.footsteps()[i].foot == Foot::left ? Foot::right : Foot::left;
    for (const double u : {0.1, 0.5, 0.9}) {
      const double t = b[1 + 2 * i] + u * p.single_support_s;
      const WalkingReference r = at(plan, t);
      ASSERT_EQ(weight(r, stance), 1.0) << "step " << i + 1;
      // r: the stance sole's centre lifted by com_height (vrp_offset 0).
      const Eigen::Vector3d vrp = sole(r, stance).head<3>() + Eigen::Vector3d(0, 0, p.com_height);
      const Eigen::Vector3d rate = (dcm(at(plan, t + h)) - dcm(at(plan, t - h))) / (2 * h);
      EXPECT_LE((rate - w * (dcm(r) - vrp)).norm(), 1e-6) << "step " << i + 1 << " u " << u;
    }
  }
}

TEST_F(TwoMetresAndATurn, ComContinuousFollowsTheDcmAndEndsAtRestBetweenTheFeet) {
  const double w = plan.omega(), h = 1e-6;
  const double speed = largest(plan, 3, 3, &WalkingReference::velocity);
  for (const double b : boundaries(plan, 0.0)) {
    EXPECT_LE((com(at(plan, b + h)) - com(at(plan, b - h))).norm(), 1.5 * 2 * h * speed)
        << "at t = " << b;
  }
  for (double t = 0.01; t < plan.end_time() + 1.0; t += 0.0173) {
    const WalkingReference r = at(plan, t);
    const Eigen::Vector3d rate = (com(at(plan, t + h)) - com(at(plan, t - h))) / (2 * h);
    EXPECT_LE((rate - r.velocity.segment<3>(3)).norm(), 1e-6) << "at t = " << t;
    EXPECT_LE((r.velocity.segment<3>(3) - w * (dcm(r) - com(r))).norm(), 1e-12);
    const Eigen::Vector3d rate_of_velocity =
        (at(plan, t + h).velocity.segment<3>(3) - at(plan, t - h).velocity.segment<3>(3)) / (2 * h);
    EXPECT_LE((rate_of_velocity - r.acceleration.segment<3>(3)).norm(), 1e-4) << "at t = " << t;
  }
  const WalkingReference end = at(plan, plan.end_time() + 5.0);
  const Eigen::Vector3d middle =
      0.5 * (sole(end, Foot::left).head<3>() + sole(end, Foot::right).head<3>()) +
      Eigen::Vector3d(0, 0, p.com_height);
  EXPECT_LE((dcm(end) - middle).norm(), 1e-12);
  EXPECT_LE((com(end) - middle).norm(), 1e-7);
  EXPECT_LE(end.velocity.segment<6>(0).norm(), 1e-6);
  // At end_time() the DCM is at rest there already; the CoM is still converging to it.
  const WalkingReference done = at(plan, plan.end_time());
  EXPECT_LE((dcm(done) - middle).norm(), 1e-12);
  EXPECT_LE(done.velocity.head<3>().norm(), 1e-12);
  EXPECT_LE((com(done) - middle).norm(), 0.01);
  std::printf(
      "CoM at end_time(): %.2f mm from the rest point; largest DCM, CoM speed %.3f, %.3f m/s\n",
      1e3 * (com(done) - middle).norm(), largest(plan, 0, 3, &WalkingReference::velocity), speed);
}

TEST_F(TwoMetresAndATurn, SwingFeetLandOnTheFootstepsAndStanceFeetStayPut) {
  const auto b = boundaries(plan, 0.0);
  for (std::size_t i = 0; i < plan.footsteps().size(); ++i) {
    const Footstep& step = plan.footsteps()[i];
    const Foot stance = step.foot == Foot::left ? Foot::right : Foot::left;
    const double lift = b[1 + 2 * i], touch = b[2 + 2 * i];
    const WalkingReference down = at(plan, touch);
    Eigen::Vector4d target;
    target << step.pose.position, step.pose.yaw;
    EXPECT_LE((sole(down, step.foot) - target).norm(), 1e-12) << "step " << i + 1;
    EXPECT_LE(down.velocity.segment<4>(6 + 4 * static_cast<int>(step.foot)).norm(), 1e-12);
    const Eigen::Vector4d planted = sole(at(plan, lift), stance);
    for (double u = 0.0; u <= 1.0; u += 0.05) {
      const WalkingReference r = at(plan, lift + u * p.single_support_s);
      EXPECT_EQ(sole(r, stance), planted) << "step " << i + 1;
      EXPECT_EQ(weight(r, stance), 1.0);
      if (u > 0.0 && u < 1.0) {
        EXPECT_EQ(weight(r, step.foot), 0.0) << "step " << i + 1 << " u " << u;
      }
    }
    const WalkingReference apex = at(plan, lift + 0.5 * p.single_support_s);
    EXPECT_NEAR(sole(apex, step.foot).z(), step.pose.position.z() + p.step_height, 1e-12);
  }
  for (double t = -0.5; t < plan.end_time() + 1.0; t += 1e-3) {
    const WalkingReference r = at(plan, t);
    for (const Foot foot : {Foot::left, Foot::right}) {
      EXPECT_GE(weight(r, foot), 0.0);
      EXPECT_LE(weight(r, foot), 1.0);
    }
  }
  // The foot that lifts first ramps 1 → 0 over the first double support, the other stays 1.
  const Foot first = plan.footsteps()[0].foot;
  EXPECT_EQ(weight(at(plan, 0.0), first), 1.0);
  EXPECT_NEAR(weight(at(plan, 0.5 * b[1]), first), 0.5, 1e-12);
  EXPECT_EQ(weight(at(plan, b[1]), first), 0.0);
}

// Steps a walk_to implies: equal straight steps within the limits, turns of
// at most max_step_turn, one to bring the feet side by side.
int expected_steps(const WalkingParameters& p, double dx, double dyaw) {
  return static_cast<int>(std::ceil(dx / p.max_step_forward) +
                          std::ceil(std::abs(dyaw) / p.max_step_turn)) +
         1;
}

void expect_within_limits(const WalkingPlan& plan, const std::array<FootPose, 2>& start) {
  const WalkingParameters& p = plan.parameters();
  std::array<FootPose, 2> feet = start;
  for (std::size_t i = 0; i < plan.footsteps().size(); ++i) {
    const Footstep& step = plan.footsteps()[i];
    const FootPose& stance = feet[step.foot == Foot::left ? 1 : 0];
    const Eigen::Vector2d d = (step.pose.position - stance.position).head<2>();
    const double c = std::cos(stance.yaw), s = std::sin(stance.yaw);
    const double ahead = c * d.x() + s * d.y(), beside = -s * d.x() + c * d.y();
    const double side = step.foot == Foot::left ? beside : -beside;
    EXPECT_LE(ahead, p.max_step_forward + 1e-9) << "step " << i + 1;
    EXPECT_GE(ahead, -p.max_step_backward - 1e-9) << "step " << i + 1;
    EXPECT_LE(std::abs(side - p.step_width), p.max_step_lateral + 1e-9) << "step " << i + 1;
    EXPECT_GE(side, p.min_step_width - 1e-9) << "step " << i + 1;
    EXPECT_LE(std::abs(std::remainder(step.pose.yaw - stance.yaw, 2 * kPi)), p.max_step_turn + 1e-9)
        << "step " << i + 1;
    if (i > 0) {
      EXPECT_NE(step.foot, plan.footsteps()[i - 1].foot) << "step " << i + 1;
    }
    feet[static_cast<int>(step.foot)] = step.pose;
  }
}

void walk_two_metres_and_turn(const WalkingParameters& p, const char* label) {
  WalkingPlan plan = standing(p);
  const WalkingReference before = at(plan, 0.0);
  const std::array<FootPose, 2> start{FootPose{sole(before, Foot::left).head<3>(), 0.0},
                                      FootPose{sole(before, Foot::right).head<3>(), 0.0}};
  ASSERT_EQ(plan.walk_to(0.0, 2.0, 0.0, kPi / 2), "");
  const int n = static_cast<int>(plan.footsteps().size());
  EXPECT_EQ(n, expected_steps(p, 2.0, kPi / 2));
  expect_within_limits(plan, start);
  // Straight steps equal in length.
  const Footstep& opening = plan.footsteps()[0];
  const double first =
      (opening.pose.position - start[static_cast<int>(opening.foot)].position).norm();
  // The end: side by side at step_width, turned by 90°, around (2, 0) from the start's middle.
  const auto& last = plan.footsteps();
  const FootPose& a = last[n - 1].pose;
  const FootPose& b = last[n - 2].pose;
  EXPECT_NEAR(std::remainder(a.yaw - kPi / 2, 2 * kPi), 0.0, 1e-12);
  EXPECT_NEAR(std::remainder(b.yaw - kPi / 2, 2 * kPi), 0.0, 1e-12);
  EXPECT_NEAR((a.position - b.position).norm(), p.step_width, 1e-12);
  const Eigen::Vector3d middle = 0.5 * (a.position + b.position);
  EXPECT_LE((middle - Eigen::Vector3d(2.1, 0.2, 0.0)).norm(), 1e-12);
  const double duration = plan.end_time();
  std::printf("%s: walk_to(2 m, 0, 90°): %d steps (first %.4f m), %.2f s, planned speed %.4f m/s\n",
              label, n, first, duration, 2.0 / duration);
}

TEST(WalkTo, TwoMetresAndATurnTakeTheStepsTheLimitsImply) {
  walk_two_metres_and_turn(WalkingParameters{}, "defaults");
  WalkingParameters icub;
  icub.com_height = 0.6;
  icub.step_width = 0.14;
  walk_two_metres_and_turn(icub, "com_height 0.6, step_width 0.14");
}

TEST(WalkTo, StraightStepsAreEqualAndSidewaysWalkingOpensOnItsSide) {
  WalkingParameters p;
  WalkingPlan plan = standing(p);
  ASSERT_EQ(plan.walk_to(0.0, 0.3, 0.22, 0.0), "");
  const auto& steps = plan.footsteps();
  EXPECT_EQ(steps.front().foot, Foot::left);  // travelling left
  const double lateral = std::min(p.max_step_lateral, p.step_width - p.min_step_width);
  const double longest = std::min(p.max_step_forward / (0.3 / std::hypot(0.3, 0.22)),
                                  lateral / (0.22 / std::hypot(0.3, 0.22)));
  const int straight = static_cast<int>(std::ceil(std::hypot(0.3, 0.22) / longest));
  ASSERT_EQ(static_cast<int>(steps.size()), straight + 1);
  for (int k = 2; k < straight; ++k) {
    EXPECT_NEAR((steps[k].pose.position - steps[k - 2].pose.position).norm(),
                2 * std::hypot(0.3, 0.22) / straight, 1e-12);
  }
  const WalkingReference r = at(plan, 0.0);
  expect_within_limits(plan, {FootPose{sole(r, Foot::left).head<3>(), 0.0},
                              FootPose{sole(r, Foot::right).head<3>(), 0.0}});
}

void expect_unchanged(const WalkingPlan& plan, const std::vector<Footstep>& steps, double end) {
  ASSERT_EQ(plan.footsteps().size(), steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(plan.footsteps()[i].pose.position, steps[i].pose.position);
  }
  EXPECT_EQ(plan.end_time(), end);
}

TEST(WalkTo, RefusesNanInfinityAndACommandWhileWalkingNamingTheValue) {
  WalkingPlan plan = standing(WalkingParameters{});
  const WalkingReference standing_before = at(plan, 3.0);
  std::string why = plan.walk_to(0.0, std::nan(""), 0.0, 0.0);
  EXPECT_NE(why.find("dx = nan"), std::string::npos) << why;
  why = plan.walk_to(0.0, 1.0, std::numeric_limits<double>::infinity(), 0.0);
  EXPECT_NE(why.find("dy = inf"), std::string::npos) << why;
  why = plan.walk_to(0.0, 1.0, 0.0, -std::numeric_limits<double>::infinity());
  EXPECT_NE(why.find("dyaw = -inf"), std::string::npos) << why;
  EXPECT_EQ(why.find('\n'), std::string::npos);
  EXPECT_TRUE(plan.footsteps().empty());
  EXPECT_FALSE(plan.walking(3.0));
  EXPECT_EQ(at(plan, 3.0).position, standing_before.position);

  ASSERT_EQ(plan.walk_to(0.0, 0.5, 0.0, 0.0), "");
  const std::vector<Footstep> steps = plan.footsteps();
  const double end = plan.end_time();
  ASSERT_TRUE(plan.walking(1.0));
  why = plan.walk_to(1.0, 0.3, 0.0, 0.0);
  EXPECT_NE(why.find("walking until t = " + std::to_string(end).substr(0, 5)), std::string::npos)
      << why;
  expect_unchanged(plan, steps, end);
  why = plan.walk_to(0.0, 101.0, 0.0, 0.0);
  EXPECT_FALSE(why.empty());
  // After the walk a new command is planned from where it ended.
  EXPECT_EQ(plan.walk_to(end + 0.5, 0.0, 0.0, -kPi / 4), "");
  EXPECT_EQ(plan.footsteps().front().foot, Foot::right);  // a right turn opens with the right foot
  EXPECT_LE((dcm(at(plan, end + 0.5)) - dcm(at(plan, end + 0.4))).norm(), 1e-12);
}

TEST(Walk, RefusesAFootstepBeyondMaxStepForwardNamingIt) {
  WalkingParameters p;
  WalkingPlan plan = standing(p);
  const WalkingReference r = at(plan, 0.0);
  std::vector<Footstep> steps{
      {Foot::left, {sole(r, Foot::left).head<3>() + Eigen::Vector3d(0.1, 0, 0), 0.0}},
      {Foot::right, {sole(r, Foot::right).head<3>() + Eigen::Vector3d(0.25, 0, 0), 0.0}}};
  const std::string why = plan.walk(0.0, steps);
  EXPECT_NE(why.find("footstep 2 (right)"), std::string::npos) << why;
  EXPECT_NE(why.find("max_step_forward = 0.12"), std::string::npos) << why;
  EXPECT_TRUE(plan.footsteps().empty());
  EXPECT_FALSE(plan.walking(0.5));
  steps[1].pose.position.x() -= 0.1;
  EXPECT_EQ(plan.walk(0.0, steps), "");
  EXPECT_EQ(plan.footsteps().size(), 2u);
  steps[1].foot = Foot::left;
  WalkingPlan again = standing(p);
  const std::string twice = again.walk(0.0, steps);
  EXPECT_NE(twice.find("footstep 2 moves the left foot again"), std::string::npos) << twice;
}

TEST(WalkingPlan, RefusesParametersOutOfRangeNamingThem) {
  WalkingParameters p;
  p.single_support_s = 0.0;
  try {
    WalkingPlan plan(p);
    ADD_FAILURE() << "accepted single_support_s = 0";
  } catch (const wbi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("single_support_s = 0"), std::string::npos) << e.what();
  }
}

TEST(WalkingPlan, VrpOffsetMovesTheDcmsRepellentPoint) {
  WalkingParameters p;
  p.vrp_offset = Eigen::Vector3d(0.02, 0.0, 0.0);
  WalkingPlan plan = standing(p);
  ASSERT_EQ(plan.walk_to(0.0, 0.5, 0.0, kPi / 4), "");
  const auto b = boundaries(plan, 0.0);
  const double h = 1e-5;
  for (std::size_t i = 0; i < plan.footsteps().size(); ++i) {
    const Foot stance = plan.footsteps()[i].foot == Foot::left ? Foot::right : Foot::left;
    const double t = b[1 + 2 * i] + 0.3 * p.single_support_s;
    const WalkingReference r = at(plan, t);
    const Eigen::Vector4d s = sole(r, stance);
    const Eigen::Vector3d vrp =
        s.head<3>() + Eigen::Vector3d(0.02 * std::cos(s[3]), 0.02 * std::sin(s[3]), p.com_height);
    const Eigen::Vector3d rate = (dcm(at(plan, t + h)) - dcm(at(plan, t - h))) / (2 * h);
    EXPECT_LE((rate - plan.omega() * (dcm(r) - vrp)).norm(), 1e-6) << "step " << i + 1;
  }
}

TEST(WalkingPlan, SampleAndWalkToAllocateNothing) {
  WalkingPlan plan = standing(WalkingParameters{});
  WalkingReference r;
  long before = wbi::test::thread_allocation_count();
  const std::string why = plan.walk_to(0.0, 2.0, 0.0, kPi / 2);
  EXPECT_EQ(wbi::test::thread_allocation_count() - before, 0) << "walk_to";
  ASSERT_EQ(why, "");
  before = wbi::test::thread_allocation_count();
  double sum = 0.0;
  for (double t = -1.0; t < plan.end_time() + 2.0; t += 1e-3) {
    plan.sample(t, r);
    sum += r.position.sum();
  }
  EXPECT_EQ(wbi::test::thread_allocation_count() - before, 0) << "sample";
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
