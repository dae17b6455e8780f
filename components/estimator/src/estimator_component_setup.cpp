// The estimator component's set-up from the robot description: the joint
// estimator and filters sized to it, and the fixed-link or legged base estimator.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <wbi/model/urdf.hpp>
#include <wbi/msg/joint_torque_sensors.hpp>
#include <wbi/runtime/console_line.hpp>

#include "estimator_component_impl.hpp"

namespace wbi::estimator {

namespace detail {

// The legged estimator, with the IMU and foot F/T sensors looked up in the description.
void EstimatorComponent::prepare_legged(const wbi::msg::RobotDescription& description,
                                        const std::vector<std::string>& joints) {
  int imus = 0;
  int force_torques = 0;
  std::map<std::string, std::pair<int, std::string>> sensor_index;  // F/T: index, frame
  imu_index_ = -1;
  foot_sensor_index_.clear();
  legged_options_.force_frames = {};
  for (const auto& sensor : description.sensors()) {
    const std::string name = sensor.name().to_string();
    if (sensor.kind() == wbi::msg::SensorKind::IMU) {
      if (imu_index_ < 0 && (imu_sensor_.empty() || name == imu_sensor_)) {
        imu_index_ = imus;
        legged_options_.imu_frame = sensor.frame().to_string();
      }
      ++imus;
    } else if (sensor.kind() == wbi::msg::SensorKind::FORCE_TORQUE) {
      sensor_index[name] = {force_torques, sensor.frame().to_string()};
      ++force_torques;
    }
  }
  if (imu_index_ < 0) {
    throw std::invalid_argument("base: legged: robot '" + robot_ + "' has no IMU" +
                                (imu_sensor_.empty() ? "" : " named '" + imu_sensor_ + "'"));
  }
  for (std::size_t foot = 0; foot < 2; ++foot) {  // the left foot's sensors first
    for (const auto& name : foot_sensors_[foot]) {
      const auto found = sensor_index.find(name);
      if (found == sensor_index.end()) {
        throw std::invalid_argument("base: legged: robot '" + robot_ + "' has no F/T sensor '" +
                                    name + "'");
      }
      foot_sensor_index_.push_back(found->second.first);
      legged_options_.force_frames[foot].push_back(found->second.second);
    }
  }
  foot_forces_.setZero(3, static_cast<Eigen::Index>(foot_sensor_index_.size()));
  needed_force_torques_ = 0;
  for (const int index : foot_sensor_index_) {
    needed_force_torques_ = std::max(needed_force_torques_, index + 1);
  }
  legged_options_.initial_position = base_pose_.topRightCorner<3, 1>();
  legged_options_.initial_yaw = std::atan2(base_pose_(1, 0), base_pose_(0, 0));
  legged_estimator_ = std::make_unique<LeggedBaseEstimator>(urdf_, joints, legged_options_);
}

// Sizes everything from the robot description, once, at the first sample.
// A description the base estimator cannot use is reported once; nothing is published.
bool EstimatorComponent::prepare(std::size_t joints) {
  if (failed_) {
    return false;
  }
  try {
    return prepare_sized(joints);
  } catch (const std::exception& e) {
    failed_ = true;
    estimator_.reset();
    const std::string text = "estimator of robot '" + robot_ + "': " + e.what();
    report().set_error(text);
    runtime::print_line(stderr, text);
    return false;
  }
}

bool EstimatorComponent::prepare_sized(std::size_t joints) {
  const auto description = description_->latest();
  if (!description || description->sample.joint_names().size() != joints) {
    return false;  // description not yet here, or not this robot's: wait
  }
  const auto n = static_cast<Eigen::Index>(joints);
  estimator_ = estimation::make_estimator(method_, n, method_parameters_);
  torque_filter_.emplace(n, cutoff_hz_);
  joints_ = joints;
  tau_.setZero(n);
  tau_in_.setZero(n);
  torque_sensor_ = wbi::msg::joint_torque_sensors(description->sample);
  const auto force_torques = static_cast<std::size_t>(std::count_if(
      description->sample.sensors().begin(), description->sample.sensors().end(),
      [](const auto& sensor) { return sensor.kind() == wbi::msg::SensorKind::FORCE_TORQUE; }));
  force_torque_filter_.reset();
  if (force_torques > 0) {
    force_torque_filter_.emplace(static_cast<Eigen::Index>(6 * force_torques), cutoff_hz_);
  }
  wrenches_.setZero(static_cast<Eigen::Index>(6 * force_torques));
  auto& state = state_;
  state.header().robot(robot_);
  state.q().assign(joints, 0.0);
  state.dq().assign(joints, 0.0);
  state.ddq().assign(joints, 0.0);
  state.tau().assign(joints, 0.0);
  state.force_torque().assign(force_torques, wbi::msg::Wrench{});
  std::vector<std::string> names;
  for (const auto& name : description->sample.joint_names()) {
    names.push_back(name.to_string());
  }
  if (base_source_ == BaseSource::fixed_link) {
    base_estimator_ =
        std::make_unique<FixedLinkBaseEstimator>(urdf_, names, fixed_link_, base_pose_);
  } else if (base_source_ == BaseSource::legged) {
    prepare_legged(description->sample, names);
  }
  torque_estimation_.reset();
  state.external_wrenches().clear();
  if (torque_config_) {
    torque_estimation_ =
        std::make_unique<TorquesFromForceTorque>(*torque_config_, description->sample, names);
    torque_estimation_->write_wrenches(state);
  }
  prepare_model_acceleration(description->sample, names);
  return true;
}

// The stream parameters the method was given (sample-rate, max-gap), else their defaults.
estimation::StreamParameters EstimatorComponent::estimator_stream() const {
  estimation::StreamParameters stream;
  if (const auto rate = method_parameters_.find("sample-rate"); rate != method_parameters_.end()) {
    stream.sample_rate_hz = rate->second;
  }
  if (const auto gap = method_parameters_.find("max-gap"); gap != method_parameters_.end()) {
    stream.max_gap_s = gap->second;
  }
  return stream;
}

namespace {

// `values` (joint name or "default" to a number) per joint; an unknown name throws, named.
Eigen::VectorXd per_joint(const std::map<std::string, double>& values, const char* parameter,
                          const std::vector<std::string>& joints) {
  const auto fallback = values.find("default");
  Eigen::VectorXd out = Eigen::VectorXd::Constant(
      static_cast<Eigen::Index>(joints.size()), fallback == values.end() ? 0.0 : fallback->second);
  for (const auto& [name, value] : values) {
    const auto at = std::find(joints.begin(), joints.end(), name);
    if (name != "default" && at == joints.end()) {
      throw std::invalid_argument(std::string(parameter) + ": the robot has no joint '" + name +
                                  "'");
    }
    if (!(value >= 0.0)) {
      throw std::invalid_argument(std::string(parameter) + ": '" + name + "' must be ≥ 0");
    }
    if (name != "default") {
      out[at - joints.begin()] = value;
    }
  }
  return out;
}

}  // namespace

// accelerations: model: the URDF's model with the configured armature (the
// torque estimation's model has the same frames: same URDF, joints and base).
void EstimatorComponent::prepare_model_acceleration(const wbi::msg::RobotDescription& description,
                                                    const std::vector<std::string>& joints) {
  model_acceleration_.reset();
  model_ddq_.reset();
  if (model_urdf_.empty()) {
    return;
  }
  if (description.floating_base() && !torque_estimation_) {
    throw std::invalid_argument(
        "accelerations: model on a floating-base robot needs joint_torques: force_torque "
        "(its contact states tell which feet the model holds)");
  }
  model::LoadOptions load;
  load.joints = joints;
  load.fixed_base = !description.floating_base();
  const Eigen::VectorXd armature = per_joint(joint_armature_, "joint_armature", joints);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    load.armature[joints[j]] = armature[static_cast<Eigen::Index>(j)];
  }
  estimation::JointLosses losses{per_joint(joint_damping_, "joint_damping", joints),
                                 per_joint(joint_friction_, "joint_friction", joints),
                                 stick_velocity_};
  model_acceleration_ = std::make_unique<AccelerationsFromModel>(
      model::load_urdf_file(model_urdf_, load), std::move(losses),
      torque_estimation_ ? &torque_estimation_->estimator() : nullptr);
  const auto n = static_cast<Eigen::Index>(joints.size());
  ddq_model_.setZero(n);
  model_ddq_ =
      std::make_unique<estimation::ModelKalmanEstimator>(n, model_kalman_, estimator_stream());
}

}  // namespace detail

}  // namespace wbi::estimator
