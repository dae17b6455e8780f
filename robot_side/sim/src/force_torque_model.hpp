// What the own plant needs to measure a F/T sensor: the part of the robot
// beyond the sensor's fixed joint (its mass per body, the contact links and
// pushes on it), built once from the URDF; the measurement itself, a
// Newton–Euler of that part, is in SimBackend::compute_sensors_after_step().
#pragma once

#include <string>
#include <vector>

#include <urdf_model/model.h>
#include <Eigen/Core>
#include <wbi/sim_models/sim_plan.hpp>

#include "wbi/model/model.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::sim {

// Mass, CoM and rotational inertia about the CoM, in some body's axes.
struct MassPiece {
  double m = 0.0;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I_c = Eigen::Matrix3d::Zero();
  // Adds a mass m2 at c2 with inertia I2 about c2 (parallel-axis theorem).
  void add(double m2, const Eigen::Vector3d& c2, const Eigen::Matrix3d& I2);
};

struct ForceTorqueModel {
  std::vector<int> bodies;         // bodies with mass beyond the joint
  std::vector<MassPiece> pieces;   // their mass beyond the joint, in body axes
  std::vector<int> contact_links;  // contact links beyond the joint (plan indices)
  std::vector<int> pushes;         // pushes on links beyond the joint (plan indices)
  Eigen::Matrix<double, 6, 1> wrench = Eigen::Matrix<double, 6, 1>::Zero();  // latest, sensor frame
};

// The model of F/T sensor `sensor` of the plan.
ForceTorqueModel force_torque_model(const robot_config::RobotConfig& config,
                                    const sim_models::SimPlan& plan, const model::Model& model,
                                    const urdf::ModelInterface& urdf_model, std::size_t sensor);

}  // namespace wbi::sim
