// SimBackend — the simulated robot behind the RobotBackend interface.
//
// Plant: forward dynamics (ABA of wbi::model) integrated with semi-implicit
// (symplectic) Euler at h = step/substeps,
//   ν_{k+1} = ν_k + h ν̇(q_k, ν_k, τ_k),   q_{k+1} = q_k ⊕ h ν_{k+1}
// where ⊕ moves the base position by h ṗ and rotates the base quaternion by
// exp(h ω) on the left (ω in world axes, mixed representation), renormalised.
// τ_k = actuator torque (commands held over the step) + joint limit springs +
// joint damping and friction; external wrenches = ground contacts + pushes.
// See robot_side/sim/README.md for every model and parameter.
//
// Use: construct with a RobotConfig (wbi::robot_config; the own plant reads
// its "wbi:" options), then the RobotBackend lifecycle
// (configure/activate). Each control period: read(t, h_c) → compute commands →
// write(t, h_c) → step(). time() is the simulation time (step() adds h_c).
// step() and read()/write() never allocate. It is the `wbi` engine of the
// sim_robot component (components/sim_robot).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "wbi/actuation/simulation_backend.hpp"
#include "wbi/model/data.hpp"
#include "wbi/model/model.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::sim {

using actuation::Duration;
using actuation::Time;
using robot_config::RobotConfig;
using robot_config::WbiOptions;

// One contact point and its state.
struct ContactPoint {
  int link = 0;                                   // index into GroundTruth::contact_links
  int frame = 0;                                  // model frame of the link
  Eigen::Vector3d p_F = Eigen::Vector3d::Zero();  // position in the link frame (sphere: centre)
  double radius = 0.0;                            // 0: a point; > 0: a sphere's
  double friction = 0.0;                          // Coulomb μ
  // state (ground truth)
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();      // world position (of the lowest point)
  Eigen::Vector3d force_W = Eigen::Vector3d::Zero();  // ground → robot force, world axes
  Eigen::Vector2d anchor = Eigen::Vector2d::Zero();   // stick anchor (x, y) on the ground
  bool in_contact = false;
  bool slipping = false;
};

// Exact state of the simulation (actuation::GroundTruth, what every engine
// offers) and the plant's contact points, for tests and benchmarks.
struct GroundTruth : actuation::GroundTruth {
  std::vector<ContactPoint> contact_points;
};

class SimBackend final : public actuation::SimulationBackend {
 public:
  explicit SimBackend(RobotConfig config);
  ~SimBackend() override;

  // step() (actuation::SimulationBackend) advances the plant by one control
  // period (config().wbi.step), in `wbi.substeps` integration steps, with the
  // commands of the last write().

  // The robot config, completed from the URDF after configure()
  // (robot_config::complete_from_urdf).
  const RobotConfig& config() const { return config_; }
  Duration step_period() const override;  // config().wbi.step in ns
  double time() const override { return time_; }
  Time stamp() const override;  // time() in ns
  const GroundTruth& ground_truth() const override { return truth_; }
  const model::Model& model() const;  // after configure()

  // Test helpers (allocate; not for the loop): overwrite the state.
  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& nu);
  // Total mechanical energy T + V (kinetic + gravitational) of the current state.
  double mechanical_energy();

 protected:
  actuation::BackendDescription on_configure() override;
  void on_activate() override;
  void on_deactivate() override;
  void on_cleanup() override;  // releases the model and the state
  void on_read(Time time, Duration period, actuation::SensorReadings& out) override;
  void on_write(Time time, Duration period, const actuation::JointCommands& in) override;
  void on_step() override;

 private:
  struct Impl;
  void substep(double h);
  void compute_contacts();
  void compute_sensors_after_step();

  RobotConfig config_;
  std::unique_ptr<Impl> impl_;
  double time_ = 0.0;
  std::int64_t step_count_ = 0;
  GroundTruth truth_;
};

}  // namespace wbi::sim
