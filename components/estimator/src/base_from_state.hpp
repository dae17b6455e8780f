// The state's base, as the estimator has just written it, in a floating-base
// model's configuration and velocity (the torque and acceleration estimates
// through the model share it).
#pragma once

#include <wbi/msg/state.h>
#include <Eigen/Core>
#include <wbi/msg/eigen.hpp>

namespace wbi::estimator::detail {

// q_model's first 7 entries (position, quaternion w x y z) and nu's first 6
// (mixed velocity: linear, then angular) from the state.
inline void base_from_state(const wbi::msg::StateEstimate& state, Eigen::VectorXd& q_model,
                            Eigen::VectorXd& nu) {
  wbi::msg::to_coordinates(state.base_pose(), q_model.head<7>());
  nu.head<6>() = wbi::msg::to_eigen(state.base_velocity());
}

}  // namespace wbi::estimator::detail
