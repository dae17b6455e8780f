// SimulationBackend: what a simulated robot offers besides the RobotBackend
// interface — a time of its own that advances by step(), and the exact state
// (ground truth). The robot driver (components/robot) runs a simulation with
// the same read → control → write loop as a real robot and adds step(): the
// simulation is then the loop's clock (lockstep or paced at real time), its
// ground truth and time go out on wbi/<robot>/ground_truth and wbi/clock.
//
// Engines (the project's own plant wbi::sim::SimBackend, MuJoCo, …) implement
// it; this header depends on no engine, so the driver library never links one.
//
// The loop of the owner, once per control period:
//   const Time t = backend.stamp();
//   backend.read(t, backend.step_period());
//   controller.update(…, backend.readings(), backend.commands());
//   backend.write(t, backend.step_period());
//   backend.step();                      // time advances by step_period()
// step(), like read() and write(), never allocates.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "wbi/actuation/robot_backend.hpp"

namespace wbi::actuation {

// Exact state of a simulation after its last step, for the ground-truth topic,
// tests and benchmarks. Mixed representation (ARCHITECTURE.md): base velocity
// (ṗ_B, ω_B) in world axes, linear first.
struct GroundTruth {
  double time = 0.0;             // [s] simulation time
  Eigen::VectorXd q;             // [nq] (base p, quaternion w,x,y,z, joints) or joints
  Eigen::VectorXd nu;            // [nv] mixed velocity (ṗ_B, ω_B world axes, q̇)
  Eigen::VectorXd dnu;           // [nv] ν̇ of the last integration step
  Eigen::VectorXd tau;           // [n] total joint torque of the last integration step
                                 // (actuators + limits + friction)
  Eigen::VectorXd tau_actuator;  // [n] actuator torque of the last integration step (the
                                 // command after the motor model and saturation)
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();
  Eigen::Vector4d base_orientation{1.0, 0.0, 0.0, 0.0};  // w, x, y, z
  Vector6d base_velocity = Vector6d::Zero();             // (ṗ, ω), world axes
  Vector6d base_acceleration = Vector6d::Zero();         // (p̈, ω̇), world axes
  std::vector<std::string> contact_links;                // links that can touch the ground
  // [n_contact_links] total ground wrench on each contact link: (force, moment
  // about the link frame origin), world axes.
  std::vector<Vector6d> contact_wrenches;
  // [n_contact_links] each contact link's frame origin, world [m] (where a foot is:
  // its slip on the ground).
  std::vector<Eigen::Vector3d> contact_positions;
  std::vector<std::string> push_links;  // [n_pushes] link of each push of the config, in order
  // [n_pushes] each push's wrench in the last integration step: (force, moment
  // about the link frame origin), world axes; zero outside its window.
  std::vector<Vector6d> push_wrenches;
};

class SimulationBackend : public RobotBackend {
 public:
  // Advances the simulation by one control period, step_period(), with the
  // commands of the last write() held over it. INACTIVE or ACTIVE (throws
  // std::logic_error otherwise); never allocates.
  void step();

  // The control period one step() covers (the read/write rate).
  virtual Duration step_period() const = 0;
  // Simulation time [s], and the same in ns (the stamp of readings and ground truth).
  virtual double time() const = 0;
  virtual Time stamp() const = 0;
  // The state after the last step (sized at configure()).
  virtual const GroundTruth& ground_truth() const = 0;

 protected:
  virtual void on_step() = 0;
};

}  // namespace wbi::actuation
