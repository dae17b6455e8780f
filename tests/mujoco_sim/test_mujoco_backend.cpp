// MujocoBackend (robot_side/mujoco_sim), driven in-process with a
// JointController or a PD + gravity law, no DDS:
//   - iCub 3 standing for 5 s, joints held in POSITION mode: the base drifts
//     < 1 mm, the foot F/T sensors carry the robot's weight (1 %), the IMU
//     reads +9.81 up (± 0.01);
//   - the same PD + gravity run on the arm in both engines ends within 1 mrad,
//     with either joint-friction model of MuJoCo;
//   - on the humanoid standing, the foot F/T sensors of both engines agree in sign
//     and size (the project's convention: the child side on the parent side);
//   - every reading is finite and stamped with the simulation time; pushes move
//     the base; the lifecycle is checked; step/read/write allocate nothing.
// Skipped with a message when the build has no MuJoCo; iCub 3 when ../shared is missing.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <Eigen/Cholesky>

#include <wbi/actuation/joint_controller.hpp>
#include <wbi/model/crba.hpp>
#include <wbi/model/data.hpp>
#include <wbi/model/kinematics.hpp>
#include <wbi/model/rnea.hpp>
#include <wbi/robot_config/robot_config.hpp>
#include <wbi/sim/sim_backend.hpp>

#include "allocation_counter.hpp"
#include "test_support.hpp"

#ifdef WBI_WITH_MUJOCO
#include <wbi/mujoco_sim/mujoco_backend.hpp>
#endif

namespace {

namespace act = wbi::actuation;
namespace rc = wbi::robot_config;

#ifndef WBI_WITH_MUJOCO
TEST(MujocoBackend, SkippedWithoutMujoco) {
  GTEST_SKIP() << "this build has no MuJoCo (install libmujoco-dev: scripts/install-deps)";
}
#else

using wbi::mujoco_sim::MujocoBackend;

constexpr double kHoldHz = 20.0;  // iCub 3 joint position hold bandwidth
constexpr double kDefaultGains = 0.0;

std::string robot_file(const std::string& name) {
  return (wbi::test::source_dir() / "deploy" / "robots" / name).string();
}

// One control period: read → control → write → step.
template <typename Backend, typename Control>
void tick(Backend& backend, Control&& control) {
  const act::Time t = backend.stamp();
  const act::Duration period = backend.step_period();
  backend.read(t, period);
  control(t, period);
  backend.write(t, period);
  backend.step();
}

// Joint PD gains for a bandwidth of f Hz, critically damped, on each joint's
// effective inertia at the initial posture, m_j = 1/(M⁻¹)_jj (the base and the
// other joints free: the smallest it can be, so the explicit PD at the control
// rate stays stable: kd h / m_j = 4π f h).
std::vector<act::PidGains> bandwidth_gains(const wbi::model::Model& m, const Eigen::VectorXd& q,
                                           double f) {
  wbi::model::Data data(m);
  const Eigen::MatrixXd M = wbi::model::mass_matrix(m, data, q);
  const Eigen::MatrixXd M_inv = M.llt().solve(Eigen::MatrixXd::Identity(m.nv, m.nv));
  const double w = 2.0 * M_PI * f;
  std::vector<act::PidGains> gains(static_cast<std::size_t>(m.n_joints));
  for (int j = 0; j < m.n_joints; ++j) {
    const double mj = 1.0 / M_inv(m.base_nv + j, m.base_nv + j);
    gains[static_cast<std::size_t>(j)].kp = mj * w * w;
    gains[static_cast<std::size_t>(j)].kd = 2.0 * mj * w;
  }
  return gains;
}

// Holds every joint at its initial position in POSITION mode, as RobotDriver's
// hold_at_start does, with bandwidth_gains at f Hz, or (f = 0) the controller's
// default gains, kp = 10·effort limit: stiff enough for the humanoid, whose
// posture tips over forward within 2 s at 20 Hz in both engines; unstable for
// iCub 3, whose URDF effort limits are 50 kN·m.
template <typename Backend>
struct Hold {
  Hold(Backend& backend, double f) : ctl(backend.description(), config(backend, f)) {
    const int n = backend.description().n_joints();
    act::JointCommandBatch batch;
    batch.modes.assign(static_cast<std::size_t>(n), wbi::ControlMode::position);
    const Eigen::VectorXd q0 = backend.ground_truth().q.tail(n);
    batch.values.assign(q0.data(), q0.data() + n);
    const auto result = ctl.submit(batch, backend.stamp());
    EXPECT_TRUE(result.ok) << result.error;
  }
  static act::JointControllerConfig config(Backend& backend, double f) {
    act::JointControllerConfig c;
    if (f > 0.0) {
      c.gains = bandwidth_gains(backend.model(), backend.ground_truth().q, f);
    }
    return c;
  }
  void operator()(Backend& backend, act::Time t, act::Duration period) {
    ctl.update(t, period, backend.readings(), backend.commands());
  }
  act::JointController ctl;
};

// Mass of the links beyond frame `root` (itself and its descendants).
double mass_beyond(const wbi::model::Model& m, int root) {
  double mass = 0.0;
  for (int f = 0; f < m.n_frames(); ++f) {
    for (int a = f; a >= 0; a = m.frame_parent[static_cast<std::size_t>(a)]) {
      if (a == root) {
        mass += m.frame_inertia[static_cast<std::size_t>(f)].m;
        break;
      }
    }
  }
  return mass;
}

Eigen::Matrix3d frame_rotation(const wbi::model::Model& m, wbi::model::Data& d,
                               const Eigen::VectorXd& q, const std::string& frame) {
  wbi::model::forward_kinematics(m, d, q);
  return wbi::model::frame_pose(m, d, m.frame_id(frame)).topLeftCorner<3, 3>();
}

TEST(MujocoBackend, ICub3StandsStillOnItsFeet) {
  const auto shared = wbi::test::shared_models_dir();
  if (!shared) {
    GTEST_SKIP() << wbi::test::kSharedMissing << " (expected "
                 << (wbi::test::source_dir().parent_path() / "shared" / "models").string() << ")";
  }
  // Ideal encoders: the default 2^14 counts (0.38 mrad) times the hold's kp make
  // the PD chatter (the chest IMU then reads 9.81 ± 0.04 m/s²), a property of the
  // controller, not of the engine.
  rc::RobotConfig config = rc::load_robot_config(robot_file("icub3.yaml"));
  config.wbi.encoders.counts_per_revolution = 0.0;
  MujocoBackend sim(config);
  sim.configure();
  sim.activate();
  Hold hold(sim, kHoldHz);
  // 1 s to settle: the joints sag under the robot's weight until the PD
  // balances it (≈ 3 mm of the base), the soles sink into the soft contact.
  auto run = [&](double seconds) {
    const auto steps = std::llround(seconds * 1e9 / static_cast<double>(sim.step_period().count()));
    for (std::int64_t k = 0; k < steps; ++k) {
      tick(sim, [&](act::Time t, act::Duration h) { hold(sim, t, h); });
    }
  };
  const Eigen::Vector3d p_start = sim.ground_truth().base_position;
  run(1.0);
  const Eigen::Vector3d p0 = sim.ground_truth().base_position;
  run(5.0);
  ASSERT_NEAR(sim.time(), 6.0, 1e-9);
  const double drift = (sim.ground_truth().base_position - p0).norm();
  EXPECT_LT(drift, 1e-3) << "base drift over 5 s [m]";

  // Vertical force through the four foot sensors (world z), against the weight
  // of what stands on them: the robot minus the four sole plates below the
  // sensors (0.72 kg of 52.4 kg: 1.4 %, more than the tolerance).
  const wbi::model::Model& m = sim.model();
  wbi::model::Data data(m);
  const auto& d = sim.description();
  sim.read(sim.stamp(), sim.step_period());
  double fz = 0.0, below = 0.0;
  for (std::size_t i = 0; i < d.ft_names.size(); ++i) {
    if (d.ft_names[i].find("foot") == std::string::npos) {
      continue;
    }
    const Eigen::Matrix3d R = frame_rotation(m, data, sim.ground_truth().q, d.ft_frames[i]);
    fz += (R * sim.readings().force_torque[i].wrench.head<3>()).z();
    below += mass_beyond(m, m.frame_id(d.ft_frames[i]));
  }
  const double g = 9.81;
  const double weight = m.total_mass * g;
  EXPECT_NEAR(fz, (m.total_mass - below) * g, 0.01 * weight)
      << "robot " << m.total_mass << " kg, sole plates " << below << " kg";
  // IMU: proper acceleration up, +g (world z of the reading)
  const auto& imu = sim.readings().imus[0];
  const Eigen::Quaterniond quat(imu.orientation[0], imu.orientation[1], imu.orientation[2],
                                imu.orientation[3]);
  EXPECT_NEAR((quat * imu.accel).z(), 9.81, 0.01);
  std::cout << "iCub 3 in MuJoCo: settling (1 s) " << (p0 - p_start).norm() * 1e3
            << " mm, then base drift over 5 s " << drift * 1e3 << " mm, foot F/T Σfz " << fz
            << " N (weight " << weight << " N, above the sensors " << (m.total_mass - below) * g
            << " N), IMU accel up " << (quat * imu.accel).z() << " m/s²\n";
}

// PD + gravity to a target posture for 3 s: τ = Kp (q* − q) − Kd q̇ + g(q), gains
// from the mass-matrix diagonal at the start (5 Hz, critically damped).
template <typename Backend>
Eigen::VectorXd pd_gravity_run(Backend& sim) {
  sim.configure();
  sim.activate();
  const wbi::model::Model& m = sim.model();
  wbi::model::Data data(m);
  const int n = m.n_joints;
  Eigen::VectorXd target(n);
  target << 0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0;
  const Eigen::VectorXd M_diag = wbi::model::mass_matrix(m, data, sim.ground_truth().q).diagonal();
  const double w = 2.0 * M_PI * 5.0;
  const Eigen::VectorXd kp = M_diag * w * w, kd = 2.0 * M_diag * w;
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  for (int k = 0; k < 3000; ++k) {
    tick(sim, [&](act::Time, act::Duration) {
      const auto& r = sim.readings();
      const Eigen::VectorXd& g = wbi::model::gravity_forces(m, data, r.position, gravity);
      auto& c = sim.commands();
      for (int j = 0; j < n; ++j) {
        c.mode[static_cast<std::size_t>(j)] = act::OutputMode::kTorque;
        c.value[j] = kp[j] * (target[j] - r.position[j]) - kd[j] * r.velocity[j] + g[j];
      }
    });
  }
  return sim.ground_truth().q;
}

// Both joint-friction models of MuJoCo (mujoco.joint_friction): the own plant's
// smoothed torque (default) and MuJoCo's frictionloss rows. Both end within
// 1 mrad of the own plant; the torque, being the own plant's model, closer.
TEST(MujocoBackend, ArmPdGravityAgreesWithTheOwnPlant) {
  const rc::RobotConfig config = rc::load_robot_config(robot_file("arm.yaml"));
  ASSERT_EQ(config.mujoco.timestep * config.mujoco.substeps, config.wbi.step)
      << "the same control period in both engines";
  ASSERT_EQ(config.mujoco.joint_friction, rc::MujocoOptions::JointFriction::kTorque);
  wbi::sim::SimBackend own(config);
  const Eigen::VectorXd q_own = pd_gravity_run(own);
  double diff_by_model[2] = {0.0, 0.0};
  for (const auto model :
       {rc::MujocoOptions::JointFriction::kTorque, rc::MujocoOptions::JointFriction::kConstraint}) {
    rc::RobotConfig c = config;
    c.mujoco.joint_friction = model;
    MujocoBackend mujoco(c);
    const Eigen::VectorXd q_mj = pd_gravity_run(mujoco);
    const bool rows = model == rc::MujocoOptions::JointFriction::kConstraint;
    // frictionloss in the MJCF only for the constraint model (the arm's joints have friction)
    EXPECT_EQ(mujoco.mjcf().find("frictionloss=\"0.") != std::string::npos, rows);
    const double diff = (q_own - q_mj).cwiseAbs().maxCoeff();
    diff_by_model[rows ? 1 : 0] = diff;
    EXPECT_LT(diff, 1e-3) << (rows ? "frictionloss" : "friction torque") << "\nown "
                          << q_own.transpose() << "\nmujoco " << q_mj.transpose();
  }
  EXPECT_LT(diff_by_model[0], diff_by_model[1]);
  std::cout << "arm PD + gravity, 3 s: engines differ by " << diff_by_model[0] * 1e3
            << " mrad at the end (friction torque), " << diff_by_model[1] * 1e3
            << " mrad (frictionloss)\n";
}

TEST(MujocoBackend, FootForceTorqueSensorsAgreeWithTheOwnPlant) {
  const rc::RobotConfig config = rc::load_robot_config(robot_file("humanoid.yaml"));
  wbi::sim::SimBackend own(config);
  MujocoBackend mujoco(config);
  auto stand = [](auto& sim) {
    sim.configure();
    sim.activate();
    Hold hold(sim, kDefaultGains);
    const Eigen::Vector3d p0 = sim.ground_truth().base_position;
    for (int k = 0; k < 2000; ++k) {
      tick(sim, [&](act::Time t, act::Duration h) { hold(sim, t, h); });
    }
    // standing: the base stays put
    EXPECT_LT((sim.ground_truth().base_position - p0).norm(), 5e-3);
    sim.read(sim.stamp(), sim.step_period());
    return sim.readings().force_torque;
  };
  const auto ft_own = stand(own);
  const auto ft_mj = stand(mujoco);
  ASSERT_EQ(ft_own.size(), 2U);
  for (std::size_t i = 0; i < ft_own.size(); ++i) {
    const auto& a = ft_own[i].wrench;
    const auto& b = ft_mj[i].wrench;
    // the dominant axis carries half the weight in both, with the same sign
    int axis = 0;
    a.head<3>().cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(b[axis], a[axis], 0.05 * std::abs(a[axis]))
        << "sensor " << i << " own " << a.transpose() << " mujoco " << b.transpose();
  }
}

TEST(MujocoBackend, EveryReadingIsFiniteAndStamped) {
  rc::RobotConfig config = rc::load_robot_config(robot_file("humanoid.yaml"));
  config.pushes.push_back(
      {"root_link", 0.2, 0.1, Eigen::Vector3d(40.0, 0.0, 0.0), Eigen::Vector3d::Zero()});
  MujocoBackend sim(config);
  sim.configure();
  sim.activate();
  Hold hold(sim, kDefaultGains);
  double max_speed = 0.0;
  for (int k = 0; k < 400; ++k) {
    tick(sim, [&](act::Time t, act::Duration h) { hold(sim, t, h); });
    max_speed = std::max(max_speed, sim.ground_truth().base_velocity.head<3>().norm());
  }
  sim.read(sim.stamp(), sim.step_period());
  const auto& r = sim.readings();
  const act::Time now = sim.stamp();
  EXPECT_EQ(now.count(), 400'000'000);
  EXPECT_TRUE(r.position.allFinite() && r.velocity.allFinite() && r.torque.allFinite() &&
              r.pwm.allFinite());
  EXPECT_EQ(r.joint_stamp, now);
  ASSERT_EQ(r.imus.size(), 1U);
  EXPECT_TRUE(r.imus[0].orientation.allFinite() && r.imus[0].gyro.allFinite() &&
              r.imus[0].accel.allFinite());
  EXPECT_NEAR(r.imus[0].orientation.norm(), 1.0, 1e-9);
  EXPECT_EQ(r.imus[0].stamp, now);
  ASSERT_EQ(r.force_torque.size(), 2U);
  for (const auto& ft : r.force_torque) {
    EXPECT_TRUE(ft.wrench.allFinite());
    EXPECT_EQ(ft.stamp, now);
  }
  const auto& truth = sim.ground_truth();
  EXPECT_DOUBLE_EQ(truth.time, 0.4);
  EXPECT_TRUE(truth.q.allFinite() && truth.nu.allFinite() && truth.dnu.allFinite() &&
              truth.tau.allFinite() && truth.tau_actuator.allFinite());
  ASSERT_EQ(truth.contact_links.size(), 2U);
  double fz = 0.0;
  for (const auto& w : truth.contact_wrenches) {
    EXPECT_TRUE(w.allFinite());
    fz += w.z();
  }
  // the ground carries the robot (a push of 40 N along x for 0.1 s is over by now)
  EXPECT_NEAR(fz, sim.model().total_mass * 9.81, 0.05 * sim.model().total_mass * 9.81);
  EXPECT_GT(max_speed, 0.01) << "the push moved the base";
}

TEST(MujocoBackend, LifecycleAndBadOptions) {
  rc::RobotConfig config = rc::load_robot_config(robot_file("arm.yaml"));
  MujocoBackend sim(config);
  EXPECT_THROW(sim.step(), std::logic_error);
  EXPECT_THROW(sim.read(act::Time(0), act::Duration(0)), std::logic_error);
  EXPECT_THROW(sim.model(), std::logic_error);
  sim.configure();
  EXPECT_NO_THROW(sim.step());  // INACTIVE: steps with every joint IDLE
  sim.activate();
  sim.step();
  EXPECT_EQ(sim.stamp().count(), 2'000'000);
  EXPECT_NE(sim.mjcf().find("<mujoco"), std::string::npos);
  sim.deactivate();
  sim.cleanup();
  EXPECT_THROW(sim.step(), std::logic_error);
  sim.configure();  // again, from the start
  EXPECT_EQ(sim.stamp().count(), 0);

  config.mujoco.timestep = 0.0;
  MujocoBackend bad(config);
  try {
    bad.configure();
    FAIL() << "timestep 0 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'mujoco.timestep'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(bad.state(), wbi::LifecycleState::unconfigured);
}

// MuJoCo resets a diverging simulation and carries on; the backend throws.
TEST(MujocoBackend, DivergenceIsAnError) {
  rc::RobotConfig config = rc::load_robot_config(robot_file("arm.yaml"));
  config.gravity = Eigen::Vector3d(0.0, 0.0, -1e12);  // accelerations beyond MuJoCo's 1e10
  MujocoBackend sim(config);
  sim.configure();
  sim.activate();
  try {
    for (int k = 0; k < 10; ++k) {
      sim.step();
    }
    FAIL() << "no error from a diverging simulation";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("diverged"), std::string::npos) << e.what();
  }
}

TEST(MujocoBackend, StepReadWriteAllocateNothing) {
  MujocoBackend sim(rc::load_robot_config(robot_file("humanoid.yaml")));
  sim.configure();
  sim.activate();
  Hold hold(sim, kDefaultGains);
  for (int k = 0; k < 10; ++k) {  // warm up (first-use allocations of the libraries)
    tick(sim, [&](act::Time t, act::Duration h) { hold(sim, t, h); });
  }
  const long before = wbi::test::thread_allocation_count();
  for (int k = 0; k < 200; ++k) {
    tick(sim, [&](act::Time t, act::Duration h) { hold(sim, t, h); });
  }
  EXPECT_EQ(wbi::test::thread_allocation_count() - before, 0);
}

#endif  // WBI_WITH_MUJOCO

}  // namespace
