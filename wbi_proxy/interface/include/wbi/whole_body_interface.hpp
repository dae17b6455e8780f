// The whole-body interface: the one type a controller is written against. It
// aggregates the four elements — Actuators, Sensors, State, Model — each an
// object of its own, acting on the controlled joints in the order the
// controller gave them (add_joints). How the robot is reached (DDS,
// in-process, other hosts) and where the model is evaluated (here or in a
// model service) is the implementation's business; the controller does not
// change. Code that needs one element takes only that one (e.g. `wbi::Model&`).
//
//   std::unique_ptr<wbi::WholeBodyInterface> robot = wbi::make_dds_interface(options);
//   robot->add_joints({"shoulder", "elbow"});
//   robot->init();  // waits for the robot's components, names the missing ones
//   wbi::RobotState s;
//   robot->state().read_robot_state(s);
//   robot->model().gravity_forces(s.q, s.world_H_base, gravity, g);
//   robot->actuators().set_control_reference(tau);
//
// The element methods are also callable on the interface itself (the original
// WBI's flat API): each is one inline call of its element, here, once for
// every implementation.
#pragma once

#include <chrono>
#include <string>

#include "wbi/actuators.hpp"
#include "wbi/model.hpp"
#include "wbi/sensors.hpp"
#include "wbi/state.hpp"

namespace wbi {

class WholeBodyInterface {
 public:
  virtual ~WholeBodyInterface() = default;

  // ---- Lifecycle ----

  // Adds joints to the controlled list, by name (before init()). Throws Error
  // naming an unknown or repeated joint.
  virtual void add_joints(const IdList& joints) = 0;

  // Connects to the robot's components and waits for them up to `timeout`.
  // Throws TimeoutError naming the missing components.
  virtual void init(std::chrono::milliseconds timeout = std::chrono::seconds(10)) = 0;

  // Disconnects, leaving the robot as it is: in streaming modes the
  // actuators' watchdog takes over when commands stop.
  virtual void close() = 0;

  // The controlled joints, in order (known from add_joints on, before init()).
  virtual const IdList& joint_list() const = 0;
  int dofs() const { return static_cast<int>(joint_list().size()); }

  // ---- The four elements (after init(); Error before) ----

  virtual Actuators& actuators() = 0;
  virtual Sensors& sensors() = 0;
  virtual State& state() = 0;
  virtual Model& model() = 0;
  virtual const Model& model() const = 0;
  virtual const Sensors& sensors() const = 0;
  virtual const State& state() const = 0;

  // ---- The flat API: each call is its element's ----

  void set_control_mode(ControlMode mode) { actuators().set_control_mode(mode); }
  void set_control_mode(ControlMode mode, int joint) { actuators().set_control_mode(mode, joint); }
  void set_control_reference(const ConstVectorRef& reference) {
    actuators().set_control_reference(reference);
  }
  void set_control_reference(double reference, int joint) {
    actuators().set_control_reference(reference, joint);
  }
  void set_control_parameter(ControlParameter parameter, const ConstVectorRef& values) {
    actuators().set_control_parameter(parameter, values);
  }
  void set_control_parameter(ControlParameter parameter, double value, int joint) {
    actuators().set_control_parameter(parameter, value, joint);
  }

  const IdList& sensor_list(SensorKind kind) const { return sensors().sensor_list(kind); }
  const IdList& external_wrench_links() const { return state().external_wrench_links(); }
  Stamp read_sensors(SensorKind kind, VectorRef values, ReadMode mode = ReadMode::latest) {
    return sensors().read_sensors(kind, values, mode);
  }
  Stamp read_sensor(SensorKind kind, int index, VectorRef values,
                    ReadMode mode = ReadMode::latest) {
    return sensors().read_sensor(kind, index, values, mode);
  }

  Stamp read_robot_state(RobotState& out, ReadMode mode = ReadMode::latest) {
    return state().read_robot_state(out, mode);
  }
  Stamp read_estimates(EstimateKind kind, VectorRef values, ReadMode mode = ReadMode::latest) {
    return state().read_estimates(kind, values, mode);
  }
  Stamp read_estimate(EstimateKind kind, int index, VectorRef values,
                      ReadMode mode = ReadMode::latest) {
    return state().read_estimate(kind, index, values, mode);
  }
  Stamp read_base_pose(Transform& world_H_base, ReadMode mode = ReadMode::latest) {
    return state().read_base_pose(world_H_base, mode);
  }
  void set_estimation_parameter(const std::string& name, double value) {
    state().set_estimation_parameter(name, value);
  }

  JointLimits joint_limits(int joint) const { return model().joint_limits(joint); }
  const IdList& frame_list() const { return model().frame_list(); }
  int frame_index(const std::string& frame) const { return model().frame_index(frame); }
  void frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                  Transform& world_H_frame) {
    model().frame_pose(q, world_H_base, frame, world_H_frame);
  }
  void jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame, MatrixRef J) {
    model().jacobian(q, world_H_base, frame, J);
  }
  void dj_nu(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
             const ConstVectorRef& base_velocity, int frame, VectorRef out) {
    model().dj_nu(q, world_H_base, dq, base_velocity, frame, out);
  }
  void mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) {
    model().mass_matrix(q, world_H_base, M);
  }
  void bias_forces(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
                   const ConstVectorRef& base_velocity, const Eigen::Vector3d& gravity,
                   VectorRef h) {
    model().bias_forces(q, world_H_base, dq, base_velocity, gravity, h);
  }
  void gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                      const Eigen::Vector3d& gravity, VectorRef g) {
    model().gravity_forces(q, world_H_base, gravity, g);
  }
  void inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                        const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                        const ConstVectorRef& ddq, const ConstVectorRef& base_acceleration,
                        const Eigen::Vector3d& gravity, VectorRef tau) {
    model().inverse_dynamics(q, world_H_base, dq, base_velocity, ddq, base_acceleration, gravity,
                             tau);
  }
  void centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                           const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                           VectorRef momentum) {
    model().centroidal_momentum(q, world_H_base, dq, base_velocity, momentum);
  }
  void centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                  MatrixRef A) {
    model().centroidal_momentum_matrix(q, world_H_base, A);
  }
  void com(const ConstVectorRef& q, const Transform& world_H_base, Eigen::Vector3d& out) {
    model().com(q, world_H_base, out);
  }
  void com_jacobian(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef J) {
    model().com_jacobian(q, world_H_base, J);
  }
};

}  // namespace wbi
