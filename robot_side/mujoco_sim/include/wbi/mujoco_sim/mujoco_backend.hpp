// MujocoBackend — MuJoCo as a simulated robot behind the RobotBackend interface,
// the `mujoco` engine of the sim_robot component (components/sim_robot).
//
// configure() builds, from the robot config, the model library's Model (the
// config's armature, LoadOptions::repair_inertia as `wbi model mjcf`) and its
// MJCF in memory (wbi::mjcf; an mjVFS, no file): the F/T sensors' child links
// welded as bodies of their own with MuJoCo force/torque sensors at their frame,
// IMU sites (framequat, gyro, accelerometer), the contact geometry and the
// ground, per-joint armature and damping, the `mujoco:` options (timestep,
// integrator, solref/solimp, cone, impratio). One step() is `mujoco.substeps`
// MuJoCo steps of `mujoco.timestep`; actuator torques go to qfrc_applied, with
// the joints' Coulomb friction as the own plant's smoothed torque
// (mujoco.joint_friction: torque) or as MuJoCo's frictionloss rows (constraint).
// Every reading is MuJoCo's state mapped to wbi's conventions
// (robot_side/mujoco_sim/README.md). The plan of the config, the held commands
// and the sensor and actuator models (encoder quantisation and noise, sensor
// noise, the PWM motor) are those of every engine (wbi::sim_models), from the
// config's `wbi:` section.
// step(), read() and write() never allocate.
#pragma once

#include <cstdint>
#include <memory>

#include "wbi/actuation/simulation_backend.hpp"
#include "wbi/model/model.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::mujoco_sim {

class MujocoBackend final : public actuation::SimulationBackend {
 public:
  explicit MujocoBackend(robot_config::RobotConfig config);
  ~MujocoBackend() override;

  // The robot config, completed from the URDF after configure().
  const robot_config::RobotConfig& config() const { return config_; }
  actuation::Duration step_period() const override;  // mujoco.timestep × mujoco.substeps
  double time() const override { return time_; }
  actuation::Time stamp() const override;
  const actuation::GroundTruth& ground_truth() const override { return truth_; }
  // After configure(): the model library's model of the robot (what the MJCF was
  // written from), and the MJCF text MuJoCo loaded.
  const model::Model& model() const;
  const std::string& mjcf() const;

 protected:
  actuation::BackendDescription on_configure() override;
  void on_activate() override {}
  void on_deactivate() override;
  void on_cleanup() override;  // releases MuJoCo's model and data
  void on_read(actuation::Time time, actuation::Duration period,
               actuation::SensorReadings& out) override;
  void on_write(actuation::Time time, actuation::Duration period,
                const actuation::JointCommands& in) override;
  void on_step() override;

 private:
  struct Impl;
  void apply_controls();
  void collect_dynamics();  // after mj_step2/mj_forward: contacts, torques, ν̇
  void collect_state();     // after mj_step1: q, ν, base

  robot_config::RobotConfig config_;
  std::unique_ptr<Impl> impl_;
  double time_ = 0.0;
  std::int64_t step_count_ = 0;
  actuation::GroundTruth truth_;
};

}  // namespace wbi::mujoco_sim
