// The estimator component's configuration and lifecycle (parameters, DDS
// endpoints), its run-time parameter changes, and its registration.
#include "wbi/estimator/estimator_component.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>

#include <Eigen/Geometry>
#include <wbi/dds/topics.hpp>
#include <wbi/runtime/console_line.hpp>
#include <wbi/runtime/producer_counters.hpp>
#include <wbi/vocabulary/joined_names.hpp>

#include "estimator_component_impl.hpp"

namespace wbi::estimator {

namespace {

std::string kebab(std::string name) {
  for (auto& c : name) {
    c = c == '_' ? '-' : c;
  }
  return name;
}

Eigen::Matrix4d pose_from(const std::vector<double>& position,
                          const std::vector<double>& quaternion) {
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H.topRightCorner<3, 1>() << position[0], position[1], position[2];
  H.topLeftCorner<3, 3>() =
      Eigen::Quaterniond(quaternion[0], quaternion[1], quaternion[2], quaternion[3])
          .toRotationMatrix();
  return H;
}

// A path parameter; a relative one is relative to the file that gives it (the deploy file).
std::string file_parameter(const runtime::Parameters& parameters, const std::string& key) {
  std::filesystem::path path = parameters.require<std::string>(key);
  if (path.is_relative() && !parameters.file().empty() && parameters.file() != "<string>") {
    path = std::filesystem::path(parameters.file()).parent_path() / path;
  }
  return path.string();
}

}  // namespace

namespace detail {

void EstimatorComponent::on_configure(const runtime::Parameters& parameters,
                                      const runtime::ComponentContext& context) {
  robot_ = parameters.require<std::string>("robot");
  method_ = parameters.get<std::string>("method", "kalman");
  method_parameters_.clear();
  for (const auto& spec : estimation::method_info(method_).parameters) {
    std::string key = spec.name;
    std::replace(key.begin(), key.end(), '-', '_');
    if (parameters.has(key)) {
      method_parameters_[spec.name] = parameters.get<double>(key, spec.default_value);
    }
  }
  estimation::make_estimator(method_, 1, method_parameters_);  // validates now, names the bad one
  cutoff_hz_ = parameters.get<double>("torque_cutoff_hz", 0.0);
  const auto base = parameters.get<std::string>("base", "fixed");
  if (base == "fixed") {
    base_source_ = BaseSource::fixed;
  } else if (base == "fixed_link") {
    base_source_ = BaseSource::fixed_link;
    urdf_ = file_parameter(parameters, "urdf");
    fixed_link_ = parameters.require<std::string>("fixed_link");
  } else if (base == "legged") {
    base_source_ = BaseSource::legged;
    urdf_ = file_parameter(parameters, "urdf");
    configure_legged(parameters);
  } else if (base == "topic") {
    base_source_ = BaseSource::topic;
  } else {
    throw runtime::ParameterError(parameters.where("base") +
                                  ": base must be fixed, fixed_link, legged or topic, got '" +
                                  base + "'");
  }
  base_pose_ =
      pose_from(parameters.get<std::vector<double>>("base_position", {0.0, 0.0, 0.0}),
                parameters.get<std::vector<double>>("base_quaternion", {1.0, 0.0, 0.0, 0.0}));
  const auto base_topic =
      parameters.get<std::string>("base_topic", dds::topics::ground_truth(robot_));
  const std::string urdf =
      urdf_.empty() && parameters.has("urdf") ? file_parameter(parameters, "urdf") : urdf_;
  torque_config_ = TorqueEstimationConfig::from(parameters, urdf);
  configure_model_accelerations(parameters, urdf);
  // Lockstep: which inputs a sample waits for (estimator_component_sample.cpp, "Inputs of a tick").
  match_ground_truth_ =
      base_source_ == BaseSource::topic && base_topic == dds::topics::ground_truth(robot_);
  lockstep_controllers_ = parameters.get<std::vector<std::string>>("lockstep_controllers", {});
  if (!lockstep_controllers_.empty() && model_urdf_.empty()) {
    throw runtime::ParameterError(parameters.where("lockstep_controllers") +
                                  ": only with accelerations: model (the controllers' commands "
                                  "are an input of the estimate only there)");
  }
  answered_.assign(lockstep_controllers_.size(), -1);
  waived_.assign(lockstep_controllers_.size(), 0);
  inputs_timeout_ = std::chrono::duration_cast<std::chrono::nanoseconds>(
      std::chrono::duration<double>(parameters.get<double>("lockstep_timeout_s", 2.0)));
  if (inputs_timeout_.count() <= 0) {
    throw runtime::ParameterError(parameters.where("lockstep_timeout_s") +
                                  ": lockstep_timeout_s must be > 0 s");
  }

  // The stamp monitor's counts, on the status topic (also summed in StateEstimate.warnings).
  dropped_ = &report().counter("dropped_samples");
  duplicated_ = &report().counter("duplicate_stamps");
  out_of_order_ = &report().counter("out_of_order_stamps");
  gaps_ = &report().counter("stamp_gaps");
  non_finite_ = &report().counter("non_finite_samples");
  wrong_size_ = &report().counter("wrong_size_samples");
  new_producers_ = &report().counter("new_producers");
  invalid_torque_estimates_ = &report().counter("invalid_torque_estimates");
  missing_force_torque_ = &report().counter("missing_force_torque_samples");
  without_model_acceleration_ = &report().counter("samples_without_model_acceleration");
  late_inputs_ = &report().counter("samples_with_late_inputs");
  // The robot's streams come from one writer each: a second robot of the same
  // name, or a rogue, is dropped and counted, not mixed into the estimate.
  // Its sensors come from the participant whose description was taken.
  const auto producer_events = runtime::count_producer_events(report());
  const auto one_producer = dds::ProducerPolicy::one(producer_events);

  auto& participant = *context.participant;
  description_ = std::make_unique<dds::Subscriber<wbi::msg::RobotDescription>>(
      participant, dds::topics::description(robot_), dds::qos::kLatched,
      [this](const wbi::msg::RobotDescription&, const dds::detail::SampleInfo&) {
        on_description();
      },
      one_producer);
  state_publisher_ = std::make_unique<dds::Publisher<wbi::msg::StateEstimate>>(
      participant, dds::topics::state(robot_), dds::qos::kStream);
  if (base_source_ == BaseSource::topic) {
    // No estimate before the first base sample: a sample waiting for it is estimated then.
    ground_truth_ = std::make_unique<dds::Subscriber<wbi::msg::GroundTruth>>(
        participant, base_topic, dds::qos::kStream,
        [this](const wbi::msg::GroundTruth& g, const dds::detail::SampleInfo&) {
          on_base_sample(g.header().seq());
        },
        one_producer);
  }
  parameter_subscriber_ = std::make_unique<dds::Subscriber<wbi::msg::EstimatorParameter>>(
      participant, dds::topics::estimator_parameters(robot_), dds::qos::kCommand,
      [this](const wbi::msg::EstimatorParameter& p, const dds::detail::SampleInfo&) {
        on_parameter(p);
      });
  if (!model_urdf_.empty()) {
    // Every controller's commands: the torques the model's accelerations come from.
    commands_ = std::make_unique<dds::Subscriber<wbi::msg::ActuatorCommand>>(
        participant, dds::topics::commands(robot_), dds::qos::kCommand,
        [this](const wbi::msg::ActuatorCommand& command, const dds::detail::SampleInfo&) {
          on_command(command);
        });
  }
  sensors_ = std::make_unique<dds::Subscriber<wbi::msg::SensorSample>>(
      participant, dds::topics::sensors(robot_), dds::qos::kStream,
      [this](const wbi::msg::SensorSample& s, const dds::detail::SampleInfo& info) {
        on_sample(s, info.writer);
      },
      dds::ProducerPolicy::owned_by(dds::description_owner(participant, *description_),
                                    producer_events));
  if (match_ground_truth_ || !lockstep_controllers_.empty()) {
    stopping_ = false;
    deferred_thread_ = std::thread([this] { run_deferred(); });
  }
}

void EstimatorComponent::on_activate() {
  std::lock_guard lock(mutex_);
  estimate_times_.clear();
  active_ = true;
  process_pending();
}

void EstimatorComponent::on_deactivate() {
  active_ = false;
  std::lock_guard lock(mutex_);
  if (estimate_times_.count() > 0) {
    runtime::print_line(stdout, "estimator of robot '" + robot_ +
                                    "': " + std::to_string(estimate_times_.count()) +
                                    " samples, from sample in to state out (its DDS write not "
                                    "included) " +
                                    estimate_times_.mean_and_p99());
  }
}

void EstimatorComponent::on_cleanup() {
  active_ = false;
  stop_deferred();   // first: it may estimate and publish
  sensors_.reset();  // first: no callback runs after this
  commands_.reset();
  parameter_subscriber_.reset();
  ground_truth_.reset();
  state_publisher_.reset();
  description_.reset();
  std::lock_guard lock(mutex_);
  estimator_.reset();
  base_estimator_.reset();
  legged_estimator_.reset();
  torque_estimation_.reset();
  model_acceleration_.reset();
  have_base_sample_ = false;
  has_deferred_ = false;
  ground_truth_seq_ = -1;
  std::fill(answered_.begin(), answered_.end(), -1);
  failed_ = false;
}

// accelerations: method (the derivative estimator's ddq) or model (model_kalman.hpp).
void EstimatorComponent::configure_model_accelerations(const runtime::Parameters& parameters,
                                                       const std::string& urdf) {
  model_urdf_.clear();
  const auto source = parameters.get<std::string>("accelerations", "method");
  if (source == "method") {
    return;
  }
  if (source != "model") {
    throw runtime::ParameterError(parameters.where("accelerations") +
                                  ": accelerations must be method or model, got '" + source + "'");
  }
  if (urdf.empty()) {
    throw runtime::ParameterError(parameters.where("accelerations") +
                                  ": accelerations: model needs the robot's urdf");
  }
  model_urdf_ = urdf;
  // The motors' armature and the joints' losses, by joint name or `default`
  // (checked against the joints at the first sample): a URDF has none of them.
  joint_armature_ = parameters.get<std::map<std::string, double>>("joint_armature", {});
  joint_damping_ = parameters.get<std::map<std::string, double>>("joint_damping", {});
  joint_friction_ = parameters.get<std::map<std::string, double>>("joint_friction", {});
  stick_velocity_ =
      parameters.get<double>("stick_velocity", estimation::JointLosses{}.stick_velocity);
  if (!(stick_velocity_ > 0.0)) {
    throw runtime::ParameterError(parameters.where("stick_velocity") +
                                  ": stick_velocity must be > 0 rad/s");
  }
  model_kalman_ = estimation::ModelKalmanParameters{};
  model_kalman_.model_order =
      parameters.get<int>("acceleration_model_order", model_kalman_.model_order);
  model_kalman_.process_noise =
      parameters.get<double>("acceleration_process_noise", model_kalman_.process_noise);
  const auto resolution = method_parameters_.find("resolution");
  if (resolution != method_parameters_.end()) {
    model_kalman_.resolution_counts = resolution->second;
  }
  estimation::ModelKalmanEstimator(1, model_kalman_);  // validates now, names the bad one
}

void EstimatorComponent::configure_legged(const runtime::Parameters& parameters) {
  legged_options_ = LeggedBaseOptions{};
  const auto feet = parameters.get<std::vector<std::string>>("feet", {"l_sole", "r_sole"});
  const auto sensors = parameters.get<std::vector<std::string>>("foot_force_torque", {});
  if (feet.size() != 2 || !(sensors.empty() || sensors.size() == 2)) {
    throw runtime::ParameterError(
        parameters.where(feet.size() != 2 ? "feet" : "foot_force_torque") +
        ": base: legged needs two feet (left, right), and none or "
        "two entries of foot F/T sensor names (one foot's several sensors joined by '+')");
  }
  legged_options_.feet = {feet[0], feet[1]};
  // "a+b": a foot on several sensors (iCub 3's front and rear plates), their loads summed.
  foot_sensors_ = {};
  for (std::size_t foot = 0; foot < sensors.size(); ++foot) {
    if (sensors[foot].empty()) {
      throw runtime::ParameterError(parameters.where("foot_force_torque") +
                                    ": foot_force_torque: an empty entry for foot " +
                                    std::to_string(foot));
    }
    foot_sensors_[foot] = split_joined_names(sensors[foot]);
    for (const auto& name : foot_sensors_[foot]) {
      if (name.empty()) {
        throw runtime::ParameterError(parameters.where("foot_force_torque") +
                                      ": foot_force_torque: an empty sensor name in '" +
                                      sensors[foot] + "'");
      }
    }
  }
  imu_sensor_ = parameters.get<std::string>("imu", "");
  legged_options_.load_force = parameters.get<double>("load_force", legged_options_.load_force);
  legged_options_.unload_force =
      parameters.get<double>("unload_force", legged_options_.unload_force);
  legged_options_.flat_ground = parameters.get<bool>("flat_ground", legged_options_.flat_ground);
  legged_options_.velocity_time_constant =
      parameters.get<double>("velocity_time_constant", legged_options_.velocity_time_constant);
  legged_options_.has_initial_position = parameters.has("base_position");
}

// Runs on a DDS thread: a rejected parameter is reported, never thrown into DDS.
void EstimatorComponent::on_parameter(const wbi::msg::EstimatorParameter& parameter) {
  try {
    apply_parameter(parameter);
  } catch (const std::exception& e) {
    const std::string text = "estimator of robot '" + robot_ + "': parameter '" +
                             parameter.name().to_string() + "' rejected: " + e.what();
    report().set_error(text);
    runtime::print_line(stderr, text);
    events().emit(EventSeverity::warning, EventKind::commands_rejected, text,
                  dds::topics::estimator_parameters(robot_));
  }
}

void EstimatorComponent::apply_parameter(const wbi::msg::EstimatorParameter& parameter) {
  std::lock_guard lock(mutex_);
  const std::string name = parameter.name().to_string();
  if (name == "reset") {
    if (estimator_) {
      estimator_->reset();
    }
    if (model_ddq_) {
      model_ddq_->reset();
    }
  } else if (name == "fixed_link") {
    if (base_estimator_) {
      base_estimator_->set_fixed_link(parameter.text().to_string());  // unknown link: throws
    }
    fixed_link_ = parameter.text().to_string();
  } else {
    auto changed = method_parameters_;
    changed[kebab(name)] = parameter.value();
    const auto n = estimator_ ? estimator_->joints() : 1;
    auto rebuilt = estimation::make_estimator(method_, n, changed);  // validates
    method_parameters_ = changed;
    if (estimator_) {
      estimator_ = std::move(rebuilt);  // allocates: a parameter change, not a sample
    }
  }
}

}  // namespace detail

void register_components(runtime::Registry& registry) {
  registry.add<detail::EstimatorComponent>(
      "estimator",
      "joint velocity/acceleration, filtered torques and base state "
      "from sensor samples");
  register_base_drift(registry);
}

}  // namespace wbi::estimator
