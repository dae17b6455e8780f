// The model's joint accelerations from commanded torques
// (estimation/model_accelerations.hpp) on the project's humanoid and arm: free,
// it is forward dynamics; held contacts do not accelerate and the dynamics hold
// with contact forces alone; a joint stuck within its friction stays, one
// pushed beyond it slides; bad sizes are named.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "model_test_common.hpp"
#include "test_support.hpp"
#include "wbi/estimation/model_accelerations.hpp"
#include "wbi/model/algorithms.hpp"

namespace wbi::test {
namespace {

using estimation::JointLosses;
using estimation::ModelAccelerations;

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

model::Model fixed_arm() {
  model::LoadOptions load;
  load.fixed_base = true;
  return model::load_urdf_file(project_model("arm7.urdf").string(), load);
}

TEST(ModelAccelerations, FreeIsForwardDynamicsLessTheSlidingLosses) {
  const model::Model m = fixed_arm();
  model::Data data(m);
  std::mt19937 rng(3);
  const Eigen::VectorXd q = model::random_configuration(m, rng);
  const Eigen::VectorXd nu = random_vector(m.nv, rng, 2.0);  // every joint faster than v_s
  const Eigen::VectorXd tau = random_vector(m.n_joints, rng, 5.0);
  const Eigen::VectorXd damping = Eigen::VectorXd::Constant(m.n_joints, 0.3);
  const Eigen::VectorXd friction = Eigen::VectorXd::Constant(m.n_joints, 0.7);
  ModelAccelerations model_ddq(m, {damping, friction}, {});
  const Eigen::VectorXd tau_net =
      tau - damping.cwiseProduct(nu) - friction.cwiseProduct(nu.cwiseSign());
  const Eigen::VectorXd expected = model::forward_dynamics(m, data, q, nu, tau_net, kGravity);
  EXPECT_TRUE(near_rel(model_ddq.update(q, nu, tau, {}), expected, 1e-12));
  EXPECT_EQ(model_ddq.stuck_joints(), 0);
}

TEST(ModelAccelerations, HeldFeetDoNotAccelerateAndOnlyTheirWrenchesAct) {
  const model::Model m = model::load_urdf_file(project_model("humanoid.urdf").string());
  model::Data data(m);
  const std::vector<int> feet = {m.frame_id("l_sole"), m.frame_id("r_sole")};
  ModelAccelerations model_ddq(m, {}, feet);
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd q = model::random_configuration(m, rng);
    const Eigen::VectorXd nu = random_vector(m.nv, rng, 0.5);
    const Eigen::VectorXd tau = random_vector(m.n_joints, rng, 10.0);
    const std::vector<char> held = {1, static_cast<char>(trial % 2)};  // both, or the left only
    const Eigen::VectorXd dnu = model_ddq.update(q, nu, tau, held);
    model::forward_velocity_kinematics(m, data, q, nu);
    Eigen::MatrixXd J(6 * (1 + held[1]), m.nv);
    for (int c = 0; c < 1 + held[1]; ++c) {
      J.middleRows<6>(6 * c) = model::frame_jacobian(m, data, feet[c]);
      const model::Vector6d a =
          J.middleRows<6>(6 * c) * dnu + model::frame_bias_acceleration(m, data, feet[c]);
      EXPECT_LT(a.norm(), 1e-8) << "foot " << c << " accelerates, trial " << trial;
    }
    // M ν̇ + h − Bτ is Jᵀλ: nothing of it outside the range of Jᵀ.
    Eigen::VectorXd generalized = Eigen::VectorXd::Zero(m.nv);
    generalized.tail(m.n_joints) = tau;
    const Eigen::VectorXd residual =
        model::inverse_dynamics(m, data, q, nu, dnu, kGravity) - generalized;
    const Eigen::VectorXd lambda = J.transpose().colPivHouseholderQr().solve(residual);
    EXPECT_LT((J.transpose() * lambda - residual).norm(), 1e-8 * (1.0 + residual.norm()))
        << "trial " << trial;
  }
}

TEST(ModelAccelerations, StuckJointsHoldWithinTheirFrictionAndSlideBeyond) {
  const model::Model m = fixed_arm();
  model::Data data(m);
  std::mt19937 rng(9);
  const Eigen::VectorXd q = model::random_configuration(m, rng);
  const Eigen::VectorXd still = Eigen::VectorXd::Zero(m.nv);
  const Eigen::VectorXd friction = Eigen::VectorXd::Constant(m.n_joints, 2.0);
  ModelAccelerations model_ddq(m, {{}, friction}, {});
  const Eigen::VectorXd gravity = model::gravity_forces(m, data, q, kGravity);
  // Gravity compensated and 1 N·m more on every joint: friction holds them all
  // (to 1e-8 rad/s²: the constraints' 1e-12 regularisation).
  Eigen::VectorXd tau = gravity + Eigen::VectorXd::Constant(m.n_joints, 1.0);
  EXPECT_LT(model_ddq.update(q, still, tau, {}).norm(), 1e-8);
  EXPECT_EQ(model_ddq.stuck_joints(), m.n_joints);
  // 10 N·m more on joint 1: it slides that way, against its friction.
  tau[1] += 10.0;
  const Eigen::VectorXd dnu = model_ddq.update(q, still, tau, {});
  EXPECT_GT(dnu[1], 0.0);
  EXPECT_EQ(model_ddq.stuck_joints(), m.n_joints - 1);
  for (int j = 0; j < m.n_joints; ++j) {
    if (j != 1) {
      EXPECT_NEAR(dnu[j], 0.0, 1e-8) << m.joint_name[j];
    }
  }
}

TEST(ModelAccelerations, BadSizesAreNamed) {
  const model::Model m = fixed_arm();
  try {
    ModelAccelerations bad(m, {Eigen::VectorXd::Zero(3), {}}, {});
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "model accelerations: damping needs 7 values ≥ 0, got 3");
  }
  const model::Model h = model::load_urdf_file(project_model("humanoid.urdf").string());
  ModelAccelerations model_ddq(h, {}, {h.frame_id("l_sole"), h.frame_id("r_sole")});
  std::mt19937 rng(1);
  const std::vector<char> one = {1};
  EXPECT_THROW(model_ddq.update(model::random_configuration(h, rng), Eigen::VectorXd::Zero(h.nv),
                                Eigen::VectorXd::Zero(h.n_joints), one),
               std::invalid_argument);
}

}  // namespace
}  // namespace wbi::test
