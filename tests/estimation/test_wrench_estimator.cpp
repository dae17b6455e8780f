// The F/T-based estimator of joint torques and external wrenches, on states
// with known wrenches: the model's own dynamics recovered to 1e-9.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "test_support.hpp"
#include "wrench_reference.hpp"

namespace wbi::test {
namespace {

using estimation::WrenchEstimator;
using estimation::WrenchEstimatorOptions;

constexpr double kTolerance = 1e-9;

WrenchEstimatorOptions humanoid_options() {
  WrenchEstimatorOptions o;
  o.sensors = {{"l_foot_ft", "l_foot_ft_sensor"}, {"r_foot_ft", "r_foot_ft_sensor"}};
  o.contact_links = {"l_sole", "r_sole"};
  o.extra_links = {"chest"};
  return o;
}

// iCub 3's eight F/T sensors (deploy/robots/icub3.yaml) and a hypothesis per submodel.
WrenchEstimatorOptions icub3_options() {
  WrenchEstimatorOptions o;
  for (const char* side : {"l", "r"}) {
    const std::string s = side;
    for (const char* part : {"leg", "foot_front", "foot_rear", "arm"}) {
      o.sensors.push_back({s + "_" + part + "_ft", s + "_" + part + "_ft_sensor"});
    }
    o.contact_links.push_back(s + "_foot_front");
    o.contact_links.push_back(s + "_foot_rear");
    o.extra_links.push_back(s + "_lower_leg");
    o.extra_links.push_back(s + "_hand");
  }
  o.extra_links.push_back("chest");
  return o;
}

// Every hypothesis link of the options, contacts first (the estimator's order).
std::vector<std::string> hypotheses(const WrenchEstimatorOptions& o) {
  std::vector<std::string> links = o.contact_links;
  links.insert(links.end(), o.extra_links.begin(), o.extra_links.end());
  return links;
}

// Random states with a wrench on every hypothesis: torques, wrenches and the
// base balance recovered from the readings.
void expect_recovered(const std::filesystem::path& urdf, const WrenchEstimatorOptions& options) {
  const model::Model m = model::load_urdf_file(urdf.string());
  WrenchEstimator estimator(m, options);
  SensorReference reference(urdf, options.sensors);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const DynamicState s = random_state(m, hypotheses(options), rng);
    const auto readings = reference.readings(m, s);
    estimator.update(s.q, s.nu, s.dnu, readings);
    EXPECT_TRUE(near_rel(estimator.joint_torques(), s.tau, kTolerance)) << "trial " << trial;
    for (std::size_t h = 0; h < s.wrenches.size(); ++h) {
      EXPECT_TRUE(
          near_rel(estimator.link_wrench(static_cast<int>(h)), s.wrenches[h].wrench, kTolerance))
          << estimator.link_names()[h] << ", trial " << trial;
    }
    EXPECT_TRUE(near_rel(estimator.base_residual(), Vector6d::Zero(), kTolerance));
    for (int j = 0; j < m.n_joints; ++j) {
      EXPECT_TRUE(estimator.joint_torque_valid(j));
    }
  }
}

TEST(WrenchEstimator, RecoversTheHumanoidsTorquesAndWrenches) {
  expect_recovered(project_model("humanoid.urdf"), humanoid_options());
}

TEST(WrenchEstimator, RecoversICub3sTorquesAndWrenches) {
  const auto dir = shared_models_dir();
  if (!dir) {
    GTEST_SKIP() << kSharedMissing;
  }
  expect_recovered(*dir / "iCubGenova09/model.urdf", icub3_options());
}

// Two hypotheses on one submodel: the data cannot tell them apart, so the
// minimum-norm solution shares the wrench, balancing the submodel exactly;
// joints whose subtree holds neither are still exact.
TEST(WrenchEstimator, SharesAWrenchTheSensorsCannotPlace) {
  const auto urdf = project_model("humanoid.urdf");
  const model::Model m = model::load_urdf_file(urdf.string());
  auto options = humanoid_options();
  options.extra_links = {"chest", "l_hand"};
  WrenchEstimator estimator(m, options);
  SensorReference reference(urdf, options.sensors);
  std::mt19937 rng(11);
  const DynamicState s = random_state(m, {"l_sole", "r_sole", "chest"}, rng);
  estimator.update(s.q, s.nu, s.dnu, reference.readings(m, s));
  model::Data data(m);
  model::forward_kinematics(m, data, s.q);
  const auto at_origin = [&](int frame, const Vector6d& w) {
    const int b = m.frame_body[frame];
    const Eigen::Vector3d p = data.p_WB[b] + data.R_WB[b] * m.frame_p_BF[frame];
    Vector6d r = w;
    r.tail<3>() += p.cross(w.head<3>());
    return r;
  };
  const Vector6d shared = at_origin(m.frame_id("chest"), estimator.link_wrench(2)) +
                          at_origin(m.frame_id("l_hand"), estimator.link_wrench(3));
  EXPECT_TRUE(near_rel(shared, at_origin(m.frame_id("chest"), s.wrenches[2].wrench), kTolerance));
  EXPECT_GT(estimator.link_wrench(3).norm(), 1.0) << "the hand gets a share";
  for (const char* joint : {"l_knee", "r_knee", "l_ankle_pitch", "r_hip_pitch"}) {
    if (!m.has_joint(joint)) {
      continue;
    }
    const int j = m.joint_id(joint);
    EXPECT_NEAR(estimator.joint_torques()[j], s.tau[j], kTolerance * 100.0) << joint;
  }
  EXPECT_TRUE(near_rel(estimator.base_residual(), Vector6d::Zero(), kTolerance));
}

TEST(WrenchEstimator, ABadReadingInvalidatesWhatItTouches) {
  const auto urdf = project_model("humanoid.urdf");
  const model::Model m = model::load_urdf_file(urdf.string());
  auto options = humanoid_options();
  options.force_limit = 1500.0;
  WrenchEstimator estimator(m, options);
  SensorReference reference(urdf, options.sensors);
  std::mt19937 rng(3);
  const DynamicState s = random_state(m, hypotheses(options), rng);
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity(), 1600.0}) {
    auto readings = reference.readings(m, s);
    readings[0][2] = bad;  // the left foot's vertical force
    estimator.update(s.q, s.nu, s.dnu, readings);
    EXPECT_FALSE(estimator.reading_valid(0));
    EXPECT_TRUE(estimator.reading_valid(1));
    EXPECT_FALSE(estimator.link_wrench_valid(0)) << "l_sole, beyond the sensor";
    EXPECT_FALSE(estimator.link_wrench_valid(2)) << "chest, on the other side";
    EXPECT_TRUE(estimator.link_wrench_valid(1)) << "r_sole";
    EXPECT_TRUE(estimator.joint_torques().allFinite());
    for (int h = 0; h < 3; ++h) {
      EXPECT_TRUE(estimator.link_wrench(h).allFinite());
    }
    const int right_knee = m.joint_id("r_knee");
    EXPECT_TRUE(estimator.joint_torque_valid(right_knee));
    EXPECT_NEAR(estimator.joint_torques()[right_knee], s.tau[right_knee], 1e-7);
    EXPECT_FALSE(estimator.joint_torque_valid(m.joint_id("l_knee")));
  }
  estimator.update(s.q, s.nu, s.dnu, reference.readings(m, s));
  for (int j = 0; j < m.n_joints; ++j) {
    EXPECT_TRUE(estimator.joint_torque_valid(j)) << m.joint_name[j];
  }
}

// Loaded above contact_on_force, unloaded below contact_off_force, unchanged between.
TEST(WrenchEstimator, ContactStatesHaveHysteresis) {
  const auto urdf = project_model("humanoid.urdf");
  const model::Model m = model::load_urdf_file(urdf.string());
  const auto options = humanoid_options();
  WrenchEstimator estimator(m, options);
  SensorReference reference(urdf, options.sensors);
  std::mt19937 rng(5);
  DynamicState s = random_state(m, hypotheses(options), rng);
  const auto states_for = [&](double force) {
    s.wrenches[0].wrench << 0.0, 0.0, force, 0.0, 0.0, 0.0;
    estimator.update(s.q, s.nu, s.dnu, reference.readings(m, s));
    return estimator.loaded(0);
  };
  EXPECT_FALSE(states_for(0.0));
  EXPECT_FALSE(states_for(8.0));
  EXPECT_TRUE(states_for(12.0));
  EXPECT_TRUE(states_for(7.0));
  EXPECT_FALSE(states_for(4.0));
  EXPECT_TRUE(estimator.is_contact_link(0));
  EXPECT_FALSE(estimator.is_contact_link(2));
}

// A link's own thresholds (the chest, hypothesis 2, at 30 / 20 N); the others keep 10 / 5 N.
TEST(WrenchEstimator, ALinkMayHaveItsOwnThresholds) {
  const auto urdf = project_model("humanoid.urdf");
  const model::Model m = model::load_urdf_file(urdf.string());
  auto options = humanoid_options();
  options.link_on_force = {{"chest", 30.0}};
  options.link_off_force = {{"chest", 20.0}};
  WrenchEstimator estimator(m, options);
  SensorReference reference(urdf, options.sensors);
  std::mt19937 rng(6);
  DynamicState s = random_state(m, hypotheses(options), rng);
  model::Data data(m);
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(m.nv);
  tau.tail(m.n_joints) = s.tau;
  const auto loaded_at = [&](double chest, double foot) {
    s.wrenches[2].wrench << chest, 0.0, 0.0, 0.0, 0.0, 0.0;
    s.wrenches[0].wrench << 0.0, 0.0, foot, 0.0, 0.0, 0.0;
    // The motion these wrenches make: else the base's imbalance lands on the chest.
    s.dnu =
        model::forward_dynamics(m, data, s.q, s.nu, tau, Eigen::Vector3d(0, 0, -9.81), s.wrenches);
    estimator.update(s.q, s.nu, s.dnu, reference.readings(m, s));
    return std::make_pair(estimator.loaded(2), estimator.loaded(0));
  };
  EXPECT_EQ(loaded_at(25.0, 12.0), std::make_pair(false, true));
  EXPECT_EQ(loaded_at(35.0, 12.0), std::make_pair(true, true));
  EXPECT_EQ(loaded_at(22.0, 7.0), std::make_pair(true, true));
  EXPECT_EQ(loaded_at(15.0, 4.0), std::make_pair(false, false));
}

std::string construction_error(const WrenchEstimatorOptions& options) {
  const model::Model m = model::load_urdf_file(project_model("humanoid.urdf").string());
  try {
    WrenchEstimator estimator(m, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(WrenchEstimator, BadConfigurationsAreNamed) {
  auto o = humanoid_options();
  o.extra_links.clear();
  o.contact_links = {"l_sole"};
  const std::string missing = construction_error(o);
  EXPECT_NE(missing.find("submodel 'r_foot' (links r_foot, r_sole; sensors r_foot_ft)"),
            std::string::npos)
      << missing;
  EXPECT_NE(missing.find("submodel 'root_link'"), std::string::npos) << missing;
  EXPECT_EQ(missing.find("submodel 'l_foot'"), std::string::npos) << missing;

  o = humanoid_options();
  o.sensors.push_back({"knee_ft", "l_knee"});
  o.sensors.push_back({"nowhere_ft", "no_such_joint"});
  o.extra_links.push_back("no_such_link");
  o.extra_links.push_back("l_sole");
  const std::string bad = construction_error(o);
  for (const char* expected :
       {"'knee_ft': joint 'l_knee' moves", "'nowhere_ft': no joint 'no_such_joint'",
        "no link 'no_such_link'", "link 'l_sole' is listed twice"}) {
    EXPECT_NE(bad.find(expected), std::string::npos) << expected << " in: " << bad;
  }

  o = humanoid_options();
  o.contact_off_force = 20.0;
  EXPECT_NE(construction_error(o).find("contact_off_force"), std::string::npos);

  o = humanoid_options();
  o.link_on_force = {{"chest", 3.0}, {"knee", 20.0}};
  const std::string thresholds = construction_error(o);
  EXPECT_NE(thresholds.find("contact threshold for 'knee', which is no wrench hypothesis"),
            std::string::npos)
      << thresholds;
  EXPECT_NE(thresholds.find("'chest': its contact off force (5.000000 N) is above its on force "
                            "(3.000000 N)"),
            std::string::npos)
      << thresholds;
}

TEST(WrenchEstimator, WrongReadingCountsAreRefused) {
  const model::Model m = model::load_urdf_file(project_model("humanoid.urdf").string());
  WrenchEstimator estimator(m, humanoid_options());
  const Eigen::VectorXd q = model::neutral_configuration(m);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m.nv);
  const std::vector<Vector6d> one(1, Vector6d::Zero());
  try {
    estimator.update(q, zero, zero, one);
    FAIL() << "one reading for two sensors was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("1 F/T readings, expected 2"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wbi::test
