// Helpers shared by the wbi::sim tests: a closed loop read → update → write → step.
#pragma once

#include <string>
#include <vector>

#include "test_support.hpp"
#include "wbi/actuation/joint_controller.hpp"
#include "wbi/sim/sim_backend.hpp"

namespace wbi::sim::test {

using actuation::JointCommandBatch;
using actuation::JointController;
using actuation::JointControllerConfig;
using actuation::PidGains;
using wbi::ControlMode;

inline std::string model_path(const std::string& file) {
  return wbi::test::project_model(file).string();
}

// The humanoid standing on the ground at the zero posture, feet F/T and IMU.
inline RobotConfig humanoid_config() {
  RobotConfig c;
  c.urdf = model_path("humanoid.urdf");
  c.initial_base_position = Eigen::Vector3d(0.0, 0.0, 0.555);
  c.place_on_ground = true;
  c.imus.push_back({"imu", "imu_frame", 0.0, 0.0});
  c.force_torque.push_back({"l_foot_ft", "l_foot_ft_sensor", 0.0, 0.0});
  c.force_torque.push_back({"r_foot_ft", "r_foot_ft_sensor", 0.0, 0.0});
  return c;
}

// Joint PD gains for the humanoid: kp = 10 s⁻¹ × effort limit, kd = kp / 200 s.
inline std::vector<PidGains> stiff_gains(const actuation::BackendDescription& d,
                                         double ki_ratio = 0.0) {
  std::vector<PidGains> g(d.joint_names.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    g[i].kp = 10.0 * d.effort_limit[i];
    g[i].kd = g[i].kp / 200.0;
    g[i].ki = ki_ratio * g[i].kp;
  }
  return g;
}

// An active simulation whose joint controller has stiff_gains, and the joint
// positions it started from (to hold them in position-direct mode).
struct StiffSim {
  explicit StiffSim(const RobotConfig& config)
      : sim(config), ctl(activated(sim), stiff(sim.description())), q_j0(initial_joints(sim)) {}

  SimBackend sim;
  JointController ctl;
  Eigen::VectorXd q_j0;

 private:
  static const actuation::BackendDescription& activated(SimBackend& s) {
    s.configure();
    s.activate();
    return s.description();
  }
  static JointControllerConfig stiff(const actuation::BackendDescription& d) {
    JointControllerConfig cc;
    cc.gains = stiff_gains(d);
    return cc;
  }
  static Eigen::VectorXd initial_joints(const SimBackend& s) {
    return s.ground_truth().q.tail(s.description().n_joints());
  }
};

// One control tick at the backend's current time.
inline void tick(SimBackend& sim, JointController& ctl) {
  const auto t = sim.stamp();
  const auto period =
      actuation::Duration(static_cast<std::int64_t>(sim.config().wbi.step * 1e9 + 0.5));
  sim.read(t, period);
  ctl.update(t, period, sim.readings(), sim.commands());
  sim.write(t, period);
  sim.step();
}

// Every joint to `mode` with `values` (all joints, model order).
inline JointCommandBatch all_joints(int n, ControlMode mode, const Eigen::VectorXd& values) {
  JointCommandBatch b;
  b.modes.assign(static_cast<std::size_t>(n), mode);
  b.values.assign(values.data(), values.data() + values.size());
  return b;
}

}  // namespace wbi::sim::test
