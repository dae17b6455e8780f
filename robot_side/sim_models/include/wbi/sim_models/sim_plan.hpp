// SimPlan: a robot config turned, once, into the flat tables every simulation
// engine steps from (in the spirit of MuJoCo's mjModel): the joint table, the
// initial state, the contact links, the pushes, the sensors with their noise,
// the layout of the ground truth. make_sim_plan() checks every name of the
// config against the model, so that each engine validates, orders and names the
// same things, and an engine keeps only its dynamics: it fills in the true
// values, and SensorNoise (sensor_noise.hpp) turns them into readings the same
// way for all.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "wbi/actuation/simulation_backend.hpp"
#include "wbi/model/model.hpp"
#include "wbi/robot_config/robot_config.hpp"
#include "wbi/sim_models/sensor_actuator_models.hpp"

namespace wbi::sim_models {

struct SimPlan {
  // ---- joints [n], in the model's order ----
  int n_joints = 0;
  int nv = 0;                    // velocity dimension (6 + n with a floating base)
  Eigen::VectorXd effort_limit;  // [N·m] (the URDF's; +inf when unlimited)
  Eigen::VectorXd damping;       // viscous [N·m·s/rad] (robot config `joints:`)
  Eigen::VectorXd friction;      // Coulomb [N·m]
  std::vector<DcMotor> motors;   // the motor behind a PWM command

  // ---- initial state ----
  // [nq] base pose (floating base) and joint positions of the config, before an
  // engine lowers the robot onto the ground (place_on_ground: its contact geometry).
  Eigen::VectorXd q0;

  // ---- ground contact ----
  bool contacts_on = false;                // wbi.contact.enable (auto: floating base only)
  std::vector<std::string> contact_links;  // links with contact geometry, first-seen order
  std::vector<int> contact_link_frames;    // [contact links] model frame of each
  std::vector<int> contact_link_of;        // [config contacts] index into contact_links
                                           // (empty when contacts are off)

  // ---- pushes: a force on a link over [start, end) of simulation time ----
  struct Push {
    std::string link;                                 // the config's link (or frame)
    int frame = 0;                                    // model frame of the link
    double start = 0.0, end = 0.0;                    // [s]
    Eigen::Vector3d force = Eigen::Vector3d::Zero();  // [N], world axes
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  // in the link frame [m]
  };
  std::vector<Push> pushes;

  // ---- sensors (their noise: SensorNoise) ----
  struct Imu {
    int frame = 0;  // model frame; its axes are the IMU's
  };
  std::vector<Imu> imus;
  struct ForceTorque {
    int frame = 0;           // model frame of the sensor: the fixed joint's child link
    std::string child_link;  // that link
  };
  std::vector<ForceTorque> force_torque;

  // What the engine offers the robot driver: joints, IMU and F/T names and frames.
  actuation::BackendDescription description;

  // Ground truth sized for this robot, zero, at q0.
  actuation::GroundTruth initial_ground_truth() const;
};

// The plan of `config` (robot_config::complete_from_urdf() done) for `model`
// (the engine's model of the same URDF). Throws std::invalid_argument
// "<where>: <item>: <what>" for an unknown joint, link or frame, a F/T joint
// that is not fixed, a zero base orientation, a push of negative duration.
SimPlan make_sim_plan(const robot_config::RobotConfig& config, const model::Model& model,
                      const std::string& where);

// The step index of time t on a grid of step h: round(t / h) (a push is active
// on steps start ≤ k < end).
inline std::int64_t step_index(double t, double h) { return std::llround(t / h); }

}  // namespace wbi::sim_models
