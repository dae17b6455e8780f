// No heap allocation in the hot path. This test compiles the library sources
// again with EIGEN_RUNTIME_NO_MALLOC (Eigen asserts on any allocation while
// Eigen::internal::set_is_malloc_allowed(false)) and also replaces the global
// operator new to count every other allocation (std::vector, std::string, …).
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "test_support.hpp"
#include "wbi/model/algorithms.hpp"

namespace wm = wbi::model;

namespace {

void check_no_allocation(const std::filesystem::path& path) {
  SCOPED_TRACE(path.string());
  // with armature on every joint, so that its terms are on the measured path too
  wm::LoadOptions options;
  for (const std::string& joint : wm::load_urdf_file(path.string()).joint_name) {
    options.armature[joint] = 0.1;
  }
  const wm::Model model = wm::load_urdf_file(path.string(), options);
  wm::Data data(model);
  std::mt19937 rng(1);
  const Eigen::VectorXd q = wm::random_configuration(model, rng);
  const Eigen::VectorXd nu = Eigen::VectorXd::Constant(model.nv, 0.3);
  const Eigen::VectorXd dnu = Eigen::VectorXd::Constant(model.nv, -0.2);
  const Eigen::Vector3d gravity(0, 0, -9.81);
  std::vector<wm::ExternalWrench> wrenches(1);
  wrenches[0].frame = model.n_frames() - 1;
  wrenches[0].wrench.setConstant(1.0);
  const int frame = model.n_frames() / 2;

  const long before = wbi::test::allocation_count();
  Eigen::internal::set_is_malloc_allowed(false);
  wm::forward_kinematics(model, data, q);
  (void)wm::frame_pose(model, data, frame);
  wm::frame_jacobian(model, data, frame);
  wm::forward_velocity_kinematics(model, data, q, nu);
  wm::frame_bias_acceleration(model, data, frame);
  wm::mass_matrix(model, data, q);
  wm::bias_forces(model, data, q, nu, gravity);
  wm::gravity_forces(model, data, q, gravity);
  wm::inverse_dynamics(model, data, q, nu, dnu, gravity, wrenches);
  wm::forward_dynamics(model, data, q, nu, dnu, gravity, wrenches);
  wm::centroidal_momentum(model, data, q, nu);
  wm::centroidal_momentum_matrix(model, data, q);
  wm::center_of_mass(model, data, q);
  wm::com_jacobian(model, data, q);
  wm::com_bias_acceleration(model, data, q, nu);
  wm::check_configuration(model, q);
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(wbi::test::allocation_count() - before, 0) << "heap allocations in the hot path";
}

}  // namespace

TEST(NoMalloc, CounterWorks) {
  const long before = wbi::test::allocation_count();
  // A direct call: clang removes the new/delete pair of an unused std::vector
  // (allocations of new-expressions may be elided), never a call of operator new.
  void* p = ::operator new(10 * sizeof(int));
  ::operator delete(p);
  EXPECT_GE(wbi::test::allocation_count() - before, 1);
}

TEST(NoMalloc, EigenCheckIsActive) {
  // an Eigen allocation while forbidden must abort, else this test proves nothing
  EXPECT_DEATH(
      {
        Eigen::internal::set_is_malloc_allowed(false);
        Eigen::VectorXd x(100);
        x.setZero();
        std::printf("%f", x.sum());
      },
      "heap allocation is forbidden");
}

TEST(NoMalloc, AlgorithmsDoNotAllocate) {
  for (const char* f : {"double_pendulum.urdf", "arm7.urdf", "humanoid.urdf"}) {
    if (std::filesystem::exists(wbi::test::project_model(f))) {
      check_no_allocation(wbi::test::project_model(f));
    }
  }
  if (const auto dir = wbi::test::shared_models_dir()) {
    check_no_allocation(*dir / "iCubGenova09/model.urdf");
    check_no_allocation(*dir / "panda/panda.urdf");
  }
}
