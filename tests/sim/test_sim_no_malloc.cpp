// No heap allocation per tick: the sim, actuation and model sources are compiled
// again into this test with EIGEN_RUNTIME_NO_MALLOC and without NDEBUG (so that
// Eigen's malloc check is live), and the global operator new counts every other
// allocation. The loop runs read → submit → update → write → step on the humanoid
// with contacts, IMU, F/T sensors, a push and noise.
#include <gtest/gtest.h>

#include "allocation_counter.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>

#include "sim_test_common.hpp"

namespace wbi::sim::test {
namespace {

#ifndef EIGEN_RUNTIME_NO_MALLOC
#error "this test must be built with EIGEN_RUNTIME_NO_MALLOC"
#endif

// `ramp`: the values move every tick (POSITION: a re-planned trajectory per tick).
void run_without_allocation(RobotConfig c, ControlMode mode, bool ramp = false) {
  c.wbi.encoders.position_noise = 1e-4;
  c.imus[0].gyro_noise = 1e-3;
  c.pushes.push_back({"root_link", 0.01, 0.02, Eigen::Vector3d(5, 0, 0), Eigen::Vector3d::Zero()});
  StiffSim held(c);
  SimBackend& sim = held.sim;
  JointController& ctl = held.ctl;
  const auto& d = sim.description();
  const Eigen::VectorXd& q_j0 = held.q_j0;
  JointCommandBatch batch = all_joints(
      d.n_joints(), mode, mode == ControlMode::torque ? Eigen::VectorXd::Zero(d.n_joints()) : q_j0);
  ctl.submit(batch, sim.stamp());
  tick(sim, ctl);  // first tick outside (nothing should allocate there either)

  const long before = wbi::test::allocation_count();
  Eigen::internal::set_is_malloc_allowed(false);
  for (int k = 0; k < 100; ++k) {
    const auto t = sim.stamp();
    const Duration period(1000000);
    sim.read(t, period);
    if (ramp) {
      for (double& value : batch.values) {
        value += 1e-4;
      }
    }
    ctl.submit(batch, t);
    ctl.update(t, period, sim.readings(), sim.commands());
    sim.write(t, period);
    sim.step();
  }
  Eigen::internal::set_is_malloc_allowed(true);
  EXPECT_EQ(wbi::test::allocation_count() - before, 0) << "operator new called in the loop";
  EXPECT_TRUE(sim.ground_truth().q.allFinite());
}

// The check itself is live in this build (not compiled out by NDEBUG).
TEST(SimNoMallocDeathTest, EigenCheckIsLive) {
  EXPECT_DEATH(
      {
        Eigen::internal::set_is_malloc_allowed(false);
        Eigen::VectorXd v = Eigen::VectorXd::Zero(100);
        std::printf("%g\n", v.sum());
      },
      "");
}

TEST(SimNoMalloc, HumanoidLoopDoesNotAllocate) {
  run_without_allocation(humanoid_config(), ControlMode::position_direct);
  RobotConfig c = humanoid_config();
  c.wbi.contact.tangential = robot_config::ContactModel::Tangential::kRegularized;
  run_without_allocation(c, ControlMode::position);
  run_without_allocation(humanoid_config(), ControlMode::position, true);
  run_without_allocation(humanoid_config(), ControlMode::torque);
}

}  // namespace
}  // namespace wbi::sim::test
