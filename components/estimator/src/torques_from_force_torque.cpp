#include "torques_from_force_torque.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <Eigen/Geometry>
#include <wbi/model/urdf.hpp>
#include <wbi/msg/eigen.hpp>

#include "base_from_state.hpp"

namespace wbi::estimator::detail {

std::optional<TorqueEstimationConfig> TorqueEstimationConfig::from(
    const runtime::Parameters& parameters, const std::string& urdf) {
  const auto source = parameters.get<std::string>("joint_torques", "sensors");
  if (source == "sensors") {
    return std::nullopt;
  }
  if (source != "force_torque") {
    throw runtime::ParameterError(parameters.where("joint_torques") +
                                  ": joint_torques must be sensors or force_torque, got '" +
                                  source + "'");
  }
  if (urdf.empty()) {
    throw runtime::ParameterError(parameters.where("joint_torques") +
                                  ": joint_torques: force_torque needs the robot's urdf");
  }
  TorqueEstimationConfig c;
  c.urdf = urdf;
  c.contact_links = parameters.require<std::vector<std::string>>("contact_links");
  c.extra_links = parameters.get<std::vector<std::string>>("extra_links", {});
  c.contact_on_force = parameters.get<double>("contact_on_force", c.contact_on_force);
  c.contact_off_force = parameters.get<double>("contact_off_force", c.contact_off_force);
  c.link_on_force = parameters.get<std::map<std::string, double>>("link_on_force", {});
  c.link_off_force = parameters.get<std::map<std::string, double>>("link_off_force", {});
  c.force_limit = parameters.get<double>("force_limit", c.force_limit);
  c.torque_limit = parameters.get<double>("torque_limit", c.torque_limit);
  const auto accelerations = parameters.get<std::string>("torque_accelerations", "none");
  if (accelerations == "estimated") {
    c.accelerations = Accelerations::estimated;
  } else if (accelerations == "imu") {
    c.accelerations = Accelerations::imu;
    c.imu = parameters.get<std::string>("imu", "");
  } else if (accelerations != "none") {
    throw runtime::ParameterError(parameters.where("torque_accelerations") +
                                  ": torque_accelerations must be none, estimated or imu, got '" +
                                  accelerations + "'");
  }
  if (c.force_limit < 0.0 || c.torque_limit < 0.0) {
    throw runtime::ParameterError(
        parameters.where(c.force_limit < 0.0 ? "force_limit" : "torque_limit") +
        ": a saturation limit is ≥ 0 (0: none)");
  }
  return c;
}

TorquesFromForceTorque::TorquesFromForceTorque(const TorqueEstimationConfig& config,
                                               const wbi::msg::RobotDescription& description,
                                               const std::vector<std::string>& joints) {
  model::LoadOptions load;
  load.joints = joints;
  load.fixed_base = !description.floating_base();
  const model::Model model = model::load_urdf_file(config.urdf, load);
  estimation::WrenchEstimatorOptions options;
  for (const auto& sensor : description.sensors()) {
    if (sensor.kind() != wbi::msg::SensorKind::FORCE_TORQUE) {
      continue;
    }
    const std::string name = sensor.name().to_string();
    const std::string frame = sensor.frame().to_string();
    if (!model.has_frame(frame)) {
      throw std::invalid_argument("F/T sensor '" + name + "': its frame '" + frame +
                                  "' is not a link of " + config.urdf);
    }
    options.sensors.push_back(
        {name, model.frame_joint[static_cast<std::size_t>(model.frame_id(frame))]});
    sensor_names_.push_back(name);
  }
  if (config.accelerations == TorqueEstimationConfig::Accelerations::imu) {
    int imus = 0;
    for (const auto& sensor : description.sensors()) {
      if (sensor.kind() == wbi::msg::SensorKind::IMU) {
        if (imu_index_ < 0 && (config.imu.empty() || sensor.name().to_string() == config.imu)) {
          imu_index_ = imus;
        }
        ++imus;
      }
    }
    if (imu_index_ < 0) {
      throw std::invalid_argument(
          "torque_accelerations: imu: the robot has no IMU" +
          (config.imu.empty() ? std::string() : " named '" + config.imu + "'"));
    }
  }
  options.contact_links = config.contact_links;
  options.extra_links = config.extra_links;
  options.contact_on_force = config.contact_on_force;
  options.contact_off_force = config.contact_off_force;
  options.link_on_force = config.link_on_force;
  options.link_off_force = config.link_off_force;
  const double inf = std::numeric_limits<double>::infinity();
  options.force_limit = config.force_limit > 0.0 ? config.force_limit : inf;
  options.torque_limit = config.torque_limit > 0.0 ? config.torque_limit : inf;
  estimator_ = std::make_unique<estimation::WrenchEstimator>(model, std::move(options));
  readings_.assign(static_cast<std::size_t>(estimator_->n_sensors()), model::Vector6d::Zero());
  q_model_.setZero(model.nq);
  nu_.setZero(model.nv);
  dnu_.setZero(model.nv);
  torques_.setZero(model.n_joints);
  accelerations_ = config.accelerations;
}

bool TorquesFromForceTorque::update(const wbi::msg::SensorSample& sample,
                                    const Eigen::Ref<const Eigen::VectorXd>& q,
                                    const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq,
                                    const wbi::msg::StateEstimate& state) {
  if (sample.force_torque().size() != readings_.size() ||
      static_cast<int>(sample.imus().size()) <= imu_index_) {
    return false;
  }
  for (std::size_t i = 0; i < readings_.size(); ++i) {
    wbi::msg::to_eigen(sample.force_torque()[i].wrench(), readings_[i]);
  }
  const model::Model& m = estimator_->model();
  using Accelerations = TorqueEstimationConfig::Accelerations;
  if (m.floating_base) {
    base_from_state(state, q_model_, nu_);
    if (accelerations_ == Accelerations::estimated) {
      dnu_.head<6>() = wbi::msg::to_eigen(state.base_acceleration());
    } else if (accelerations_ == Accelerations::imu) {
      // The accelerometer reads the proper acceleration f = Rᵀ (a − g): a = R f + g.
      const auto& imu = sample.imus()[static_cast<std::size_t>(imu_index_)];
      dnu_.head<3>() =
          wbi::msg::to_eigen(imu.orientation()) * wbi::msg::to_eigen(imu.linear_acceleration()) +
          estimator_->options().gravity;
    }
  }
  q_model_.tail(m.n_joints) = q;
  nu_.tail(m.n_joints) = dq;
  if (accelerations_ == Accelerations::estimated) {
    dnu_.tail(m.n_joints) = ddq;
  }
  estimator_->update(q_model_, nu_, dnu_, readings_);
  invalid_joints_ = 0;
  for (int j = 0; j < m.n_joints; ++j) {
    if (estimator_->joint_torque_valid(j)) {
      torques_[j] = estimator_->joint_torques()[j];
    } else {
      ++invalid_joints_;
    }
  }
  invalid_wrenches_ = 0;
  for (std::size_t h = 0; h < estimator_->link_names().size(); ++h) {
    invalid_wrenches_ += estimator_->link_wrench_valid(static_cast<int>(h)) ? 0 : 1;
  }
  return true;
}

std::string TorquesFromForceTorque::missing_readings(const wbi::msg::SensorSample& sample) const {
  std::string names;
  for (std::size_t i = sample.force_torque().size(); i < sensor_names_.size(); ++i) {
    names += (names.empty() ? "" : ", ") + sensor_names_[i];
  }
  if (static_cast<int>(sample.imus().size()) <= imu_index_ &&
      sample.force_torque().size() == sensor_names_.size()) {
    return "joint_torques: force_torque: torque_accelerations: imu: sensor samples carry " +
           std::to_string(sample.imus().size()) + " IMU readings, the IMU is number " +
           std::to_string(imu_index_ + 1) + "; torques and wrenches are held";
  }
  return "joint_torques: force_torque: sensor samples carry " +
         std::to_string(sample.force_torque().size()) + " F/T readings, the description " +
         std::to_string(sensor_names_.size()) +
         (names.empty() ? std::string(" (more readings than sensors)")
                        : " (missing: " + names + ")") +
         "; torques and wrenches are held";
}

void TorquesFromForceTorque::write_wrenches(wbi::msg::StateEstimate& state) const {
  auto& out = state.external_wrenches();
  const auto& links = estimator_->link_names();
  if (out.size() != links.size()) {  // the first time only
    out.assign(links.size(), wbi::msg::ExternalWrenchEstimate{});
    for (std::size_t h = 0; h < links.size(); ++h) {
      out[h].link(links[h]);
      out[h].contact(estimator_->is_contact_link(static_cast<int>(h)));
    }
  }
  for (std::size_t h = 0; h < links.size(); ++h) {
    const int i = static_cast<int>(h);
    const model::Vector6d& w = estimator_->link_wrench(i);
    wbi::msg::to_wire(w, out[h].wrench());
    out[h].loaded(estimator_->loaded(i));
    out[h].valid(estimator_->link_wrench_valid(i));
  }
}

}  // namespace wbi::estimator::detail
