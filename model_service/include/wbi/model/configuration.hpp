// Building and checking q; helpers for tests and tools (these allocate; not for
// the hot path unless stated).
#pragma once

#include <random>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "wbi/model/model.hpp"

namespace wbi::model {

// q at the base origin with identity orientation and all joints at 0.
Eigen::VectorXd neutral_configuration(const Model& model);

// q from a base pose and joint positions (size n_joints). For a fixed-base model
// the base pose must be the identity (throws otherwise).
Eigen::VectorXd make_configuration(const Model& model, const Eigen::Vector3d& p_WB,
                                   const Eigen::Quaterniond& quat_WB, const Eigen::VectorXd& s);
// Same, the base pose as a 4×4 homogeneous transform world_H_base.
Eigen::VectorXd make_configuration(const Model& model, const Eigen::Matrix4d& world_H_base,
                                   const Eigen::VectorXd& s);

// Throws std::invalid_argument when q has the wrong size, is not finite or its
// quaternion is not unit (|‖quat‖ − 1| > 1e-6). No allocation.
void check_configuration(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q);

// q ⊕ ν dt: base position += ṗ dt, orientation ← exp(ω dt) · orientation (world
// axes), joints += q̇ dt.
Eigen::VectorXd integrate(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& nu,
                          double dt);

// A random q: base position in [−1,1]³, random unit quaternion, joints uniform in
// their limits intersected with [−π, π] (revolute) or [−1, 1] m (prismatic).
Eigen::VectorXd random_configuration(const Model& model, std::mt19937& rng);

}  // namespace wbi::model
