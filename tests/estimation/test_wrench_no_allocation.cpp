// WrenchEstimator::update() allocates nothing: this file, the estimator's and
// the model's sources are compiled with EIGEN_RUNTIME_NO_MALLOC (Eigen asserts
// on a heap allocation in the checked region) and operator new is counted.
#ifndef EIGEN_RUNTIME_NO_MALLOC
#error "this test must be built with EIGEN_RUNTIME_NO_MALLOC"
#endif

#include <gtest/gtest.h>

#include <random>

#include "allocation_counter.hpp"
#include "test_support.hpp"
#include "wbi/estimation/model_accelerations.hpp"
#include "wbi/estimation/wrench_estimator.hpp"
#include "wbi/model/configuration.hpp"
#include "wbi/model/urdf.hpp"

namespace wbi::test {
namespace {

TEST(WrenchEstimatorNoAllocation, UpdateWithOneAndSeveralHypothesesPerSubmodel) {
  const model::Model m = model::load_urdf_file(project_model("humanoid.urdf").string());
  estimation::WrenchEstimatorOptions options;
  options.sensors = {{"l_foot_ft", "l_foot_ft_sensor"}, {"r_foot_ft", "r_foot_ft_sensor"}};
  options.contact_links = {"l_sole", "r_sole"};
  options.extra_links = {"chest", "l_hand", "r_hand"};  // three on the root submodel
  estimation::WrenchEstimator estimator(m, options);
  std::mt19937 rng(2);
  const Eigen::VectorXd q = model::random_configuration(m, rng);
  const Eigen::VectorXd nu = Eigen::VectorXd::Constant(m.nv, 0.3);
  const Eigen::VectorXd dnu = Eigen::VectorXd::Constant(m.nv, -0.2);
  std::vector<model::Vector6d> readings(2, model::Vector6d::Constant(5.0));
  std::vector<model::Vector6d> bad = readings;
  bad[1][0] = std::nan("");

  const long before = allocation_count();
  Eigen::internal::set_is_malloc_allowed(false);
  for (int k = 0; k < 100; ++k) {
    estimator.update(q, nu, dnu, k % 10 == 0 ? bad : readings);
  }
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(allocation_count() - before, 0);
  EXPECT_TRUE(estimator.joint_torques().allFinite());
}

// ModelAccelerations::update() with both feet held and stuck joints to release.
TEST(ModelAccelerationsNoAllocation, UpdateWithContactsAndFriction) {
  const model::Model m = model::load_urdf_file(project_model("humanoid.urdf").string());
  const Eigen::VectorXd friction = Eigen::VectorXd::Constant(m.n_joints, 0.3);
  estimation::ModelAccelerations accelerations(m, {friction * 2.0, friction},
                                               {m.frame_id("l_sole"), m.frame_id("r_sole")});
  std::mt19937 rng(4);
  const Eigen::VectorXd q = model::random_configuration(m, rng);
  Eigen::VectorXd nu = Eigen::VectorXd::Zero(m.nv);
  nu.tail(5).setConstant(0.5);  // some joints slide, the others may stick
  const Eigen::VectorXd tau = Eigen::VectorXd::Constant(m.n_joints, 3.0);
  const std::vector<std::vector<char>> held = {{1, 1}, {1, 0}, {0, 0}};
  accelerations.update(q, nu, tau, held[0]);
  const long before = allocation_count();
  Eigen::internal::set_is_malloc_allowed(false);
  for (int k = 0; k < 30; ++k) {
    accelerations.update(q, nu, tau, held[static_cast<std::size_t>(k % 3)]);
  }
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(allocation_count() - before, 0);
}

}  // namespace
}  // namespace wbi::test
