// The whole-body interface: the one abstract type a controller is written
// against. Its four elements — Actuators, Sensors, State, Model — act on the
// controlled joints, in the order the controller gave them (add_joints). How
// the robot is reached (DDS, in-process, other hosts) is the implementation's
// business; the controller does not change.
//
//   std::unique_ptr<wbi::WholeBodyInterface> robot = wbi::make_dds_interface(options);
//   robot->add_joints({"shoulder", "elbow"});
//   robot->init();                       // waits for the robot's components, names the missing
//   ones robot->read_estimates(wbi::EstimateKind::joint_position, q); robot->gravity_forces(q,
//   world_H_base, gravity, g); robot->set_control_reference(tau);
#pragma once

#include <chrono>

#include "wbi/actuators.hpp"
#include "wbi/model.hpp"
#include "wbi/sensors.hpp"
#include "wbi/state.hpp"

namespace wbi {

class WholeBodyInterface : public Actuators, public Sensors, public State, public Model {
 public:
  ~WholeBodyInterface() override = default;

  // Adds joints to the controlled list, by name (before init()). Throws Error
  // naming an unknown or repeated joint.
  virtual void add_joints(const IdList& joints) = 0;

  // Connects to the robot's components and waits for them up to `timeout`.
  // Throws TimeoutError naming the missing components.
  virtual void init(std::chrono::milliseconds timeout = std::chrono::seconds(10)) = 0;

  // Disconnects, leaving the robot as it is: in streaming modes the
  // actuators' watchdog takes over when commands stop.
  virtual void close() = 0;
};

}  // namespace wbi
