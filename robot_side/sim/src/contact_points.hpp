// The own plant's contact points: the config's contact geometry as points on
// the links (box: the 4 corners of its −z face; sphere: its centre with its
// radius; capsule: its two end spheres), and how far a posture is above the ground.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <wbi/sim_models/sim_plan.hpp>

#include "wbi/model/data.hpp"
#include "wbi/model/model.hpp"
#include "wbi/robot_config/robot_config.hpp"
#include "wbi/sim/sim_backend.hpp"

namespace wbi::sim {

std::vector<ContactPoint> contact_points(const robot_config::RobotConfig& config,
                                         const sim_models::SimPlan& plan);

// How far the robot at q must go down for its lowest contact point to touch the
// ground at height `ground` (negative: up).
double height_above_ground(const model::Model& m, model::Data& kinematics, const Eigen::VectorXd& q,
                           const std::vector<ContactPoint>& points, double ground);

}  // namespace wbi::sim
