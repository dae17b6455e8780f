// A controller's rig: a robot simulated in lockstep in this process (its base
// estimated from the ground truth), and the DDS whole-body interface of one
// controller on the given joints, initialised. The benchmarks of the balancing
// and walking ticks time what their controller does with it; tests drive a
// controller's library on it without a process of its own.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <wbi/dds_interface.hpp>

#include "wbi/sim_rig/in_process_robot.hpp"

namespace wbi::sim_rig {

class LockstepControllerRig {
 public:
  // sim_parameters: sim_robot's, after robot: (engine, config).
  LockstepControllerRig(const std::string& robot, const std::string& sim_parameters,
                        const std::string& controller, const std::string& urdf,
                        const std::vector<std::string>& joints)
      : rig_(robot,
             "robot: " + robot + "\n" + sim_parameters + "lockstep: true\nlockstep_controllers: [" +
                 controller + "]\n",
             "robot: " + robot + "\nbase: topic\nmethod: backward-difference\ncutoff: 50\n") {
    DdsInterfaceOptions options;
    options.robot = robot;
    options.controller = controller;
    options.urdf = urdf;
    options.max_age_s = 5.0;
    interface_ = make_dds_interface(options);
    interface_->add_joints(joints);
    rig_.start_simulation();
    interface_->init(std::chrono::seconds(20));
  }
  ~LockstepControllerRig() {
    rig_.sim().shutdown();
    rig_.estimator().shutdown();
  }
  LockstepControllerRig(const LockstepControllerRig&) = delete;
  LockstepControllerRig& operator=(const LockstepControllerRig&) = delete;

  WholeBodyInterface& robot() { return *interface_; }
  // The joint positions of the latest estimate: a controller's posture.
  Eigen::VectorXd measured_posture() {
    Eigen::VectorXd q(interface_->dofs());
    interface_->read_estimates(EstimateKind::joint_position, q);
    return q;
  }

 private:
  sim_rig::InProcessRobot rig_;
  std::unique_ptr<WholeBodyInterface> interface_;
};

}  // namespace wbi::sim_rig
