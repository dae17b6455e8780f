// Base pose and mixed velocity of a robot standing on its feet, from what a real
// robot measures: the IMU (orientation, gyro), the joint state and the feet's
// normal forces. Equations: components/estimator/README.md ("base: legged").
//   R_B  = R_yaw · R_WI · (R_BI(q))ᵀ          orientation from the IMU, yaw anchored at start
//   p_B  = Σ w_i (a_i − r_i(q)) / Σ w_i       r_i = p_foot_i − p_B, a_i the anchor of foot i
//   ω_B  = R_yaw R_WI ω_gyro − J_I,ω,joints q̇   (the IMU frame's own joint motion removed)
//   v_B  = −Σ w_i (J_i,v,ω ω_B + J_i,v,joints q̇) / Σ w_i    J_i,v ν = 0 for each loaded foot
//   then blended with the accelerometer's integral (complementary filter, time constant τ)
// A foot is loaded while its normal force is above a threshold (with hysteresis);
// its anchor is set from the current estimate when it becomes loaded, so the base
// pose stays continuous when feet are lifted and put down. Allocates nothing per
// update after construction.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <wbi/model/data.hpp>
#include <wbi/model/model.hpp>

#include "wbi/estimator/base_estimator.hpp"

namespace wbi::estimator {

struct LeggedBaseOptions {
  std::array<std::string, 2> feet{"l_sole", "r_sole"};  // frames at the soles' contact plane
  std::string imu_frame = "imu_frame";                  // the IMU's frame in the model
  // Each foot's F/T sensor frames (each force is given in its sensor's axes; a
  // foot on several sensors, as iCub 3's front and rear plates, carries their
  // sum); none: not measured, the foot counts as loaded with weight 1.
  std::array<std::vector<std::string>, 2> force_frames{};
  // The first base position; unset: x, y = 0 and z such that the (weighted) soles are at z = 0.
  bool has_initial_position = false;
  Eigen::Vector3d initial_position = Eigen::Vector3d::Zero();
  double initial_yaw = 0.0;  // [rad] the base's yaw at start (the IMU's yaw is re-anchored to it)
  // A foot becomes loaded above load_force and unloaded below unload_force [N].
  double load_force = 40.0;
  double unload_force = 20.0;
  // A foot put down is on the ground where it stood before (its anchor keeps its
  // height): no height drift from the contact's give at every step. false: the
  // anchor's height is taken from the current estimate (stairs, uneven ground).
  bool flat_ground = true;
  // Complementary filter of the linear velocity [s]: the accelerometer's high
  // frequencies, the legs' kinematics below 1/(2π τ). 0: the kinematics alone.
  double velocity_time_constant = 0.05;
  double gravity = 9.81;  // [m/s²] for the accelerometer (proper acceleration)
};

// One IMU reading, as the sensor sample carries it.
struct ImuInput {
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // R_WI (its own world)
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();                   // [rad/s] IMU axes
  Eigen::Vector3d accelerometer = Eigen::Vector3d::Zero();          // p̈ − g [m/s²], IMU axes
};

class LeggedBaseEstimator {
 public:
  // Loads the model (joints in the robot's order). Throws std::invalid_argument
  // naming an unknown frame or joint, bad thresholds, or a fixed-base model.
  LeggedBaseEstimator(const std::string& urdf, const std::vector<std::string>& joints,
                      const LeggedBaseOptions& options);

  // stamp_ns: the sample's source stamp; q, dq, ddq: joint state in the robot's
  // order; imu: the IMU reading;
  // sensor_force: the force each F/T sensor of force_frames measures [N], the left
  // foot's sensors first, then the right's, one column each (the foot on the leg,
  // in the sensor's axes; the world-vertical parts of a foot's sensors add up to
  // its load). A non-finite input (or a zero quaternion) leaves the estimate as it
  // was. Throws std::invalid_argument on wrong sizes.
  const BaseState& update(std::int64_t stamp_ns, const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& dq,
                          const Eigen::Ref<const Eigen::VectorXd>& ddq, const ImuInput& imu,
                          const Eigen::Ref<const Eigen::Matrix3Xd>& sensor_force);
  // The number of F/T sensors, columns of update()'s sensor_force.
  int force_sensors() const {
    return static_cast<int>(force_frames_[0].size() + force_frames_[1].size());
  }

  bool loaded(int foot) const { return loaded_[static_cast<std::size_t>(foot)]; }
  // Where each foot is anchored in the world (valid once it has been loaded).
  const Eigen::Vector3d& anchor(int foot) const { return anchor_[static_cast<std::size_t>(foot)]; }
  const wbi::model::Model& model() const { return model_; }

 private:
  void start(const Eigen::Vector2d& weights);
  double force_world_z(const Eigen::Vector3d& force, int frame);
  Eigen::Vector3d blend_velocity(std::int64_t stamp_ns, const Eigen::Vector3d& kinematic,
                                 const Eigen::Vector3d& omega,
                                 const Eigen::Vector3d& imu_acceleration);
  void kinematics(const Eigen::Ref<const Eigen::VectorXd>& q, const Eigen::Matrix3d& world_R_base);

  wbi::model::Model model_;
  wbi::model::Data data_;
  LeggedBaseOptions options_;
  std::array<int, 2> feet_{};
  int imu_ = 0;
  std::array<std::vector<int>, 2> force_frames_{};  // per foot, its sensors' frames
  bool started_ = false;
  Eigen::Matrix3d yaw_offset_ = Eigen::Matrix3d::Identity();
  std::array<bool, 2> loaded_{};
  std::array<Eigen::Vector3d, 2> anchor_{};
  // Per update, at the estimated orientation with the base at the origin:
  std::array<Eigen::Vector3d, 2> r_{};  // sole origins relative to the base, world axes
  Eigen::Vector3d r_imu_ = Eigen::Vector3d::Zero();  // the IMU's origin relative to the base
  std::array<Eigen::Matrix<double, 6, Eigen::Dynamic>, 2> J_;  // the soles' Jacobians
  Eigen::Matrix<double, 3, Eigen::Dynamic> J_imu_angular_;     // the IMU frame's, angular rows
  std::array<Eigen::Matrix<double, 6, 1>, 2> dJnu_{};
  Eigen::VectorXd q_model_;  // [nq]
  Eigen::VectorXd nu_;       // [nv]
  BaseState state_;
  std::int64_t last_stamp_ns_ = 0;  // the velocity filter's previous sample
  Eigen::Vector3d last_omega_ = Eigen::Vector3d::Zero();
};

}  // namespace wbi::estimator
