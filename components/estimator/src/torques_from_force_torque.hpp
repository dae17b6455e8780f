// The estimator component's `joint_torques: force_torque`: joint torques and
// external wrenches from the robot's F/T sensors through the model
// (wbi::estimation::WrenchEstimator), for robots without joint-torque sensors.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <wbi/msg/description.h>
#include <wbi/msg/sensors.h>
#include <wbi/msg/state.h>
#include <Eigen/Core>
#include <wbi/estimation/wrench_estimator.hpp>

#include <wbi/runtime/parameters.hpp>
#include "wbi/estimator/legged_base_estimator.hpp"

namespace wbi::estimator::detail {

// The deploy-file parameters; absent unless joint_torques is force_torque.
struct TorqueEstimationConfig {
  std::string urdf;
  std::vector<std::string> contact_links;
  std::vector<std::string> extra_links;
  double contact_on_force = 10.0;
  double contact_off_force = 5.0;
  std::map<std::string, double> link_on_force;  // per link, instead of the two above
  std::map<std::string, double> link_off_force;
  double force_limit = 0.0;   // 0: no limit
  double torque_limit = 0.0;  // 0: no limit
  // What accelerations enter the dynamics. none (the default): the estimate is
  // quasi-static (velocity terms, gravity and the readings). estimated: the
  // state's q̈ and base acceleration; measured in balancing (README), the
  // accelerations differentiated from encoders and the legged base were noisier
  // than the inertial terms they add. imu: the base's linear acceleration is the
  // IMU's (its accelerometer turned into the world by its orientation, gravity
  // added back), q̈ and the angular acceleration 0: a push's reaction is in the
  // submodels' balance from its first tick.
  enum class Accelerations { none, estimated, imu };
  Accelerations accelerations = Accelerations::none;
  std::string imu;  // the estimator's `imu`: its name in the description ("": the first)

  // joint_torques: sensors (the default, no config) or force_torque. Throws
  // runtime::ParameterError naming the parameter.
  static std::optional<TorqueEstimationConfig> from(const runtime::Parameters& parameters,
                                                    const std::string& urdf);
};

class TorquesFromForceTorque {
 public:
  // The model in the robot's joint order, every F/T sensor of the description
  // (its frame is the child link of its fixed joint). Throws
  // std::invalid_argument naming what does not fit.
  TorquesFromForceTorque(const TorqueEstimationConfig& config,
                         const wbi::msg::RobotDescription& description,
                         const std::vector<std::string>& joints);

  // One sample: q, dq, ddq of the joints, the base as in `state` (pose,
  // velocity, acceleration already written). False, with the sample left
  // unused, when it lacks F/T readings or, with accelerations: imu, the IMU's
  // (counted by the caller). Never allocates.
  bool update(const wbi::msg::SensorSample& sample, const Eigen::Ref<const Eigen::VectorXd>& q,
              const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq,
              const wbi::msg::StateEstimate& state);

  // Why update() refused a sample: the sensors whose readings it lacks.
  std::string missing_readings(const wbi::msg::SensorSample& sample) const;

  // Joint torques of the last update (an invalid joint keeps its last valid value).
  const Eigen::VectorXd& torques() const { return torques_; }
  // Joints and hypotheses whose estimate the last update could not make.
  int invalid_joints() const { return invalid_joints_; }
  int invalid_wrenches() const { return invalid_wrenches_; }
  // The wrench estimator, its model and its link wrenches (accelerations: model).
  const estimation::WrenchEstimator& estimator() const { return *estimator_; }
  // The external wrenches, written into the state (sized once, here).
  void write_wrenches(wbi::msg::StateEstimate& state) const;

 private:
  std::unique_ptr<estimation::WrenchEstimator> estimator_;
  std::vector<model::Vector6d> readings_;
  std::vector<std::string> sensor_names_;
  Eigen::VectorXd q_model_, nu_, dnu_, torques_;
  int invalid_joints_ = 0;
  int invalid_wrenches_ = 0;
  TorqueEstimationConfig::Accelerations accelerations_ =
      TorqueEstimationConfig::Accelerations::none;  // none: dnu_ stays zero
  int imu_index_ = -1;                              // in the samples' imus, with accelerations: imu
};

}  // namespace wbi::estimator::detail
