// What a simulated run did to the robot, from its ground truth: how far each
// contact link travelled on the ground (a standing robot's foot slip), how
// often each joint sat at a position limit, and the largest actuator torque
// against the effort limit. Printed when the simulation stops, so that an
// experiment's run reports what only the simulator knows (deploy/README.md,
// "Running iCub 3 and TALOS"). add() never allocates.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <wbi/actuation/robot_backend.hpp>
#include <wbi/actuation/simulation_backend.hpp>

namespace wbi::robot {

class GroundTruthSummary {
 public:
  // A joint is at a limit within this distance of it (or beyond) [rad].
  static constexpr double kLimitTolerance = 1e-3;

  GroundTruthSummary(const actuation::BackendDescription& description,
                     const actuation::GroundTruth& first);

  void add(const actuation::GroundTruth& truth);

  std::uint64_t ticks() const { return ticks_; }
  // Largest horizontal distance of a contact link's frame from where it was at
  // the first tick [m], and which link; -1 without contact links.
  double largest_slip() const;
  int slipping_link() const;
  // Largest fraction of the ticks one joint spent at a limit, and which joint.
  double largest_limit_fraction() const;
  int joint_most_at_limit() const;
  // Largest |actuator torque| / effort limit over the run, and which joint.
  double largest_effort_fraction() const;
  int joint_nearest_effort() const;

  // Three lines, each "<who>: <what>: <figure> (<where>)".
  void print(std::ostream& out, const std::string& who) const;

 private:
  std::vector<std::string> joint_names_;
  std::vector<std::string> contact_links_;
  Eigen::VectorXd lower_, upper_, effort_;
  std::vector<Eigen::Vector3d> start_;   // contact link positions at the first tick
  Eigen::VectorXd slip_;                 // [links] largest horizontal travel [m]
  std::vector<std::uint64_t> at_limit_;  // [joints] ticks at a limit
  Eigen::VectorXd torque_;               // [joints] largest |τ_actuator| [N·m]
  std::uint64_t ticks_ = 0;
};

}  // namespace wbi::robot
