#include "wbi/estimator/legged_base_estimator.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/LU>
#include <wbi/model/algorithms.hpp>

#include "floating_base_model.hpp"

namespace wbi::estimator {

namespace {

int frame_of(const wbi::model::Model& model, const std::string& frame, const char* what) {
  if (!model.has_frame(frame)) {
    throw std::invalid_argument("legged base estimate of " + model.name + ": unknown " + what +
                                " frame '" + frame + "'");
  }
  return model.frame_id(frame);
}

}  // namespace

LeggedBaseEstimator::LeggedBaseEstimator(const std::string& urdf,
                                         const std::vector<std::string>& joints,
                                         const LeggedBaseOptions& options)
    : model_(detail::load_floating_base_model(urdf, joints)),
      data_(model_),
      options_(options),
      J_imu_angular_(3, model_.nv),
      q_model_(Eigen::VectorXd::Zero(model_.nq)),
      nu_(Eigen::VectorXd::Zero(model_.nv)) {
  for (std::size_t i = 0; i < 2; ++i) {
    feet_[i] = frame_of(model_, options.feet[i], "foot");
    J_[i].setZero(6, model_.nv);
  }
  imu_ = frame_of(model_, options.imu_frame, "IMU");
  for (std::size_t i = 0; i < 2; ++i) {
    for (const auto& frame : options.force_frames[i]) {
      force_frames_[i].push_back(frame_of(model_, frame, "force/torque sensor"));
    }
  }
  if (!(options.unload_force >= 0.0 && options.load_force >= options.unload_force)) {
    throw std::invalid_argument(
        "legged base estimate: need 0 <= unload_force <= load_force, got unload_force " +
        std::to_string(options.unload_force) + " N, load_force " +
        std::to_string(options.load_force) + " N");
  }
  if (!(options.velocity_time_constant >= 0.0)) {
    throw std::invalid_argument(
        "legged base estimate: velocity_time_constant must be >= 0 s, got " +
        std::to_string(options.velocity_time_constant));
  }
}

// Forward kinematics at the estimated orientation with the base at the origin:
// r_i, the soles' and the IMU's Jacobians (the base position does not enter them).
void LeggedBaseEstimator::kinematics(const Eigen::Ref<const Eigen::VectorXd>& q,
                                     const Eigen::Matrix3d& world_R_base) {
  detail::set_base(q_model_, Eigen::Vector3d::Zero(), world_R_base);
  q_model_.tail(model_.n_joints) = q;
  wbi::model::forward_kinematics(model_, data_, q_model_);
  for (std::size_t i = 0; i < 2; ++i) {
    r_[i] = wbi::model::frame_pose(model_, data_, feet_[i]).topRightCorner<3, 1>();
    J_[i] = wbi::model::frame_jacobian(model_, data_, feet_[i]);
  }
  r_imu_ = wbi::model::frame_pose(model_, data_, imu_).topRightCorner<3, 1>();
  J_imu_angular_ = wbi::model::frame_jacobian(model_, data_, imu_).bottomRows<3>();
}

// Anchors both feet where the initial base position puts them (r_ current).
void LeggedBaseEstimator::start(const Eigen::Vector2d& weights) {
  Eigen::Vector3d position = options_.initial_position;
  if (!options_.has_initial_position) {  // the soles on the ground, z = 0
    position.z() = -(weights[0] * r_[0].z() + weights[1] * r_[1].z()) / weights.sum();
  }
  for (std::size_t i = 0; i < 2; ++i) {
    anchor_[i] = position + r_[i];
  }
}

double LeggedBaseEstimator::force_world_z(const Eigen::Vector3d& force, int frame) {
  return wbi::model::frame_pose(model_, data_, frame).row(2).head<3>().dot(force);
}

// Complementary filter: v̂ ← v̂ + Δt a_B, pulled towards the kinematic velocity with
// the gain Δt / (τ + Δt). a_B, the base origin's acceleration, from the IMU's:
// a_B = a_I + ω̇ × (p_B − p_I) + ω × (ω × (p_B − p_I)) (the IMU on the base link).
Eigen::Vector3d LeggedBaseEstimator::blend_velocity(std::int64_t stamp_ns,
                                                    const Eigen::Vector3d& kinematic,
                                                    const Eigen::Vector3d& omega,
                                                    const Eigen::Vector3d& imu_acceleration) {
  const double dt = 1e-9 * static_cast<double>(stamp_ns - last_stamp_ns_);
  const bool continuous = started_ && dt > 0.0 && dt < 0.1;
  Eigen::Vector3d velocity = kinematic;
  if (continuous && options_.velocity_time_constant > 0.0) {
    const Eigen::Vector3d imu_to_base = -r_imu_;
    const Eigen::Vector3d omega_dot = (omega - last_omega_) / dt;
    const Eigen::Vector3d acceleration =
        imu_acceleration + omega_dot.cross(imu_to_base) + omega.cross(omega.cross(imu_to_base));
    const Eigen::Vector3d predicted = state_.velocity.head<3>() + dt * acceleration;
    velocity = predicted + dt / (options_.velocity_time_constant + dt) * (kinematic - predicted);
  }
  if (!continuous || stamp_ns > last_stamp_ns_) {
    last_stamp_ns_ = stamp_ns;
    last_omega_ = omega;
  }
  return velocity;
}

const BaseState& LeggedBaseEstimator::update(
    std::int64_t stamp_ns, const Eigen::Ref<const Eigen::VectorXd>& q,
    const Eigen::Ref<const Eigen::VectorXd>& dq, const Eigen::Ref<const Eigen::VectorXd>& ddq,
    const ImuInput& imu, const Eigen::Ref<const Eigen::Matrix3Xd>& sensor_force) {
  const auto n = model_.n_joints;
  if (q.size() != n || dq.size() != n || ddq.size() != n) {
    throw std::invalid_argument("legged base estimate: joint vectors must have size " +
                                std::to_string(n));
  }
  if (sensor_force.cols() < force_sensors()) {
    throw std::invalid_argument("legged base estimate: " + std::to_string(sensor_force.cols()) +
                                " F/T forces for " + std::to_string(force_sensors()) + " sensors");
  }
  if (!q.allFinite() || !dq.allFinite() || !ddq.allFinite() ||
      !imu.orientation.coeffs().allFinite() || imu.orientation.norm() < 0.5 ||
      !imu.gyro.allFinite() || !imu.accelerometer.allFinite() || !sensor_force.allFinite()) {
    return state_;  // a broken reading: the estimate stays as it was
  }

  // Orientation: the IMU's, moved to the base (R_BI from the joints), yaw anchored at start.
  const Eigen::Matrix3d world_R_imu = imu.orientation.normalized().toRotationMatrix();
  detail::set_base(q_model_, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity());
  q_model_.tail(n) = q;
  wbi::model::forward_kinematics(model_, data_, q_model_);
  const Eigen::Matrix3d base_R_imu =
      wbi::model::frame_pose(model_, data_, imu_).topLeftCorner<3, 3>();
  const Eigen::Matrix3d measured = world_R_imu * base_R_imu.transpose();
  if (!started_) {
    const double yaw = std::atan2(measured(1, 0), measured(0, 0));
    yaw_offset_ = Eigen::AngleAxisd(options_.initial_yaw - yaw, Eigen::Vector3d::UnitZ()).matrix();
  }
  const Eigen::Matrix3d world_R_base = yaw_offset_ * measured;
  kinematics(q, world_R_base);

  // Which feet carry weight (hysteresis on the world-vertical force); unmeasured: loaded.
  Eigen::Vector2d weights;
  Eigen::Index sensor = 0;  // columns of sensor_force, the left foot's first
  std::array<bool, 2> touched_down{};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    double f = force_frames_[i].empty() ? std::numeric_limits<double>::quiet_NaN() : 0.0;
    for (const int frame : force_frames_[i]) {
      f += force_world_z(sensor_force.col(sensor++), frame);
    }
    const bool was_loaded = loaded_[i];
    loaded_[i] = std::isnan(f) || f > (was_loaded ? options_.unload_force : options_.load_force);
    weights[k] = !loaded_[i] ? 0.0 : std::isnan(f) ? 1.0 : f;
    touched_down[i] = loaded_[i] && !was_loaded;
  }
  const bool first = !started_;
  if (first) {
    start(weights.sum() > 0.0 ? weights : Eigen::Vector2d(1.0, 1.0));
    touched_down = {false, false};  // just anchored
  }

  // Feet that stand on their anchors: loaded and not just put down. None (a flight
  // phase, or both just put down): every foot counts equally on its last anchor.
  Eigen::Vector2d standing = weights;
  for (std::size_t i = 0; i < 2; ++i) {
    standing[static_cast<Eigen::Index>(i)] *= touched_down[i] ? 0.0 : 1.0;
  }
  if (!(standing.sum() > 0.0)) {
    standing.setOnes();
  }
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 2; ++i) {
    position += standing[static_cast<Eigen::Index>(i)] * (anchor_[i] - r_[i]);
  }
  position /= standing.sum();
  for (std::size_t i = 0; i < 2; ++i) {
    if (touched_down[i]) {
      const double ground = anchor_[i].z();
      anchor_[i] = position + r_[i];  // a foot put down stays where it landed
      if (options_.flat_ground) {
        anchor_[i].z() = ground;
      }
    }
  }
  state_.world_H_base.topLeftCorner<3, 3>() = world_R_base;
  state_.world_H_base.topRightCorner<3, 1>() = position;

  // Velocity: ω from the gyro; v from J_i,v ν = 0 of the loaded feet (weighted least squares).
  const Eigen::Vector2d velocity_weights = weights.sum() > 0.0 ? weights : standing;
  const Eigen::Matrix3d world_R_imu_anchored = yaw_offset_ * world_R_imu;
  const Eigen::Vector3d omega = world_R_imu_anchored * imu.gyro - J_imu_angular_.rightCols(n) * dq;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < 2; ++i) {
    velocity -= velocity_weights[static_cast<Eigen::Index>(i)] *
                (J_[i].block<3, 3>(0, 3) * omega + J_[i].topRows<3>().rightCols(n) * dq);
  }
  velocity /= velocity_weights.sum();
  const Eigen::Vector3d imu_acceleration =
      world_R_imu_anchored * imu.accelerometer - Eigen::Vector3d(0.0, 0.0, options_.gravity);
  velocity = blend_velocity(stamp_ns, velocity, omega, imu_acceleration);
  started_ = true;
  state_.velocity << velocity, omega;

  // Acceleration: J_i ν̇ + J̇_i ν = 0 of each loaded foot, weighted.
  nu_ << state_.velocity, dq;
  detail::set_base(q_model_, position, world_R_base);
  wbi::model::forward_velocity_kinematics(model_, data_, q_model_, nu_);
  state_.acceleration.setZero();
  for (std::size_t i = 0; i < 2; ++i) {
    const double w = velocity_weights[static_cast<Eigen::Index>(i)];
    if (w > 0.0) {
      const Eigen::PartialPivLU<Eigen::Matrix<double, 6, 6>> J_base(J_[i].leftCols<6>());
      const Eigen::Matrix<double, 6, 1> rhs =
          J_[i].rightCols(n) * ddq + wbi::model::frame_bias_acceleration(model_, data_, feet_[i]);
      state_.acceleration -= w * J_base.solve(rhs);
    }
  }
  state_.acceleration /= velocity_weights.sum();
  return state_;
}

}  // namespace wbi::estimator
