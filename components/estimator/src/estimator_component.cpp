#include "wbi/estimator/estimator_component.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include <Eigen/Geometry>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/estimation/estimator_factory.hpp>
#include <wbi/estimation/low_pass_filter.hpp>
#include <wbi/runtime/console_line.hpp>
#include <wbi/runtime/producer_counters.hpp>

#include "wbi/estimator/base_estimator.hpp"
#include "wbi/estimator/legged_base_estimator.hpp"

namespace wbi::estimator {

namespace {

// "a+b+c" → {a, b, c}; "a" → {a}.
std::vector<std::string> split_at_plus(const std::string& text) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (auto plus = text.find('+'); plus != std::string::npos; plus = text.find('+', begin)) {
    parts.push_back(text.substr(begin, plus - begin));
    begin = plus + 1;
  }
  parts.push_back(text.substr(begin));
  return parts;
}

enum class BaseSource { fixed, fixed_link, legged, topic };

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

void write_pose(wbi::msg::Pose& pose, const Eigen::Matrix4d& H) {
  const Eigen::Quaterniond q(Eigen::Matrix3d(H.topLeftCorner<3, 3>()));
  pose.position().x(H(0, 3));
  pose.position().y(H(1, 3));
  pose.position().z(H(2, 3));
  pose.orientation().w(q.w());
  pose.orientation().x(q.x());
  pose.orientation().y(q.y());
  pose.orientation().z(q.z());
}

// A path parameter; a relative one is relative to the file that gives it (the deploy file).
std::string file_parameter(const runtime::Parameters& parameters, const std::string& key) {
  std::filesystem::path path = parameters.require<std::string>(key);
  if (path.is_relative() && !parameters.file().empty() && parameters.file() != "<string>") {
    path = std::filesystem::path(parameters.file()).parent_path() / path;
  }
  return path.string();
}

class EstimatorComponent final : public runtime::Component {
 public:
  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
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

    // The stamp monitor's counts, on the status topic (also summed in StateEstimate.warnings).
    dropped_ = &report().counter("dropped_samples");
    duplicated_ = &report().counter("duplicate_stamps");
    out_of_order_ = &report().counter("out_of_order_stamps");
    gaps_ = &report().counter("stamp_gaps");
    non_finite_ = &report().counter("non_finite_samples");
    wrong_size_ = &report().counter("wrong_size_samples");
    new_producers_ = &report().counter("new_producers");
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
          [this](const wbi::msg::GroundTruth&, const dds::detail::SampleInfo&) {
            on_base_sample();
          },
          one_producer);
    }
    parameter_subscriber_ = std::make_unique<dds::Subscriber<wbi::msg::EstimatorParameter>>(
        participant, dds::topics::estimator_parameters(robot_), dds::qos::kCommand,
        [this](const wbi::msg::EstimatorParameter& p, const dds::detail::SampleInfo&) {
          on_parameter(p);
        });
    sensors_ = std::make_unique<dds::Subscriber<wbi::msg::SensorSample>>(
        participant, dds::topics::sensors(robot_), dds::qos::kStream,
        [this](const wbi::msg::SensorSample& s, const dds::detail::SampleInfo& info) {
          on_sample(s, info.writer);
        },
        dds::ProducerPolicy::owned_by(dds::description_owner(participant, *description_),
                                      producer_events));
  }

  void on_activate() override {
    std::lock_guard lock(mutex_);
    active_ = true;
    process_pending();
  }
  void on_deactivate() override { active_ = false; }

  void on_cleanup() override {
    active_ = false;
    sensors_.reset();  // first: no callback runs after this
    parameter_subscriber_.reset();
    ground_truth_.reset();
    state_publisher_.reset();
    description_.reset();
    std::lock_guard lock(mutex_);
    estimator_.reset();
    base_estimator_.reset();
    legged_estimator_.reset();
    have_base_sample_ = false;
    failed_ = false;
  }

  void on_shutdown() override { on_cleanup(); }

 private:
  void configure_legged(const runtime::Parameters& parameters) {
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
      foot_sensors_[foot] = split_at_plus(sensors[foot]);
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

  // The legged estimator, with the IMU and foot F/T sensors looked up in the description.
  void prepare_legged(const wbi::msg::RobotDescription& description,
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
  bool prepare(std::size_t joints) {
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

  bool prepare_sized(std::size_t joints) {
    const auto description = description_->latest();
    if (!description || description->sample.joint_names().size() != joints) {
      return false;  // description not yet here, or not this robot's: wait
    }
    const auto n = static_cast<Eigen::Index>(joints);
    estimator_ = estimation::make_estimator(method_, n, method_parameters_);
    torque_filter_.emplace(n, cutoff_hz_);
    q_.setZero(n);
    tau_.setZero(n);
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
    return true;
  }

  // A sample that came before activation or before the description is kept and
  // estimated once both are there: a lockstep robot sends its next sample only
  // after this one has been answered.
  void on_description() {
    std::lock_guard lock(mutex_);
    process_pending();
  }

  void on_base_sample() {
    std::lock_guard lock(mutex_);
    have_base_sample_ = true;
    process_pending();
  }

  // Every input of an estimate is there: active, the description, the base sample (topic).
  bool ready(std::size_t joints) {
    return active_ && (base_source_ != BaseSource::topic || have_base_sample_) &&
           (estimator_ || prepare(joints));
  }

  void process_pending() {  // caller holds mutex_
    if (pending_ && ready(pending_->encoder_position().size())) {
      estimate(*pending_);
      pending_.reset();
    }
  }

  void on_sample(const wbi::msg::SensorSample& sample, const dds::detail::Guid& writer) {
    std::lock_guard lock(mutex_);
    if (writer != producer_) {
      on_new_producer(writer);
    }
    if (!ready(sample.encoder_position().size())) {
      pending_ = sample;  // start-up only: not active, no description or no base sample yet
      return;
    }
    estimate(sample);
  }

  // Samples from another writer than the last one: the robot restarted (a new
  // process, whose stamps and sequence numbers start again; the sensor reader
  // moves to a new writer only when the one it took is gone, dds/producers.hpp). Every filter
  // starts afresh from its samples, sized again from its description: continued, they would ignore
  // its samples as out of order until its stamps passed the old ones, or differentiate across the
  // jump. Allocates: an event, not a tick.
  void on_new_producer(const dds::detail::Guid& writer) {  // caller holds mutex_
    const bool first = producer_ == dds::detail::Guid{};
    producer_ = writer;
    if (first) {
      return;
    }
    new_producers_->add();
    const std::string text = "estimator of robot '" + robot_ + "': sensor samples from a new " +
                             "writer " + dds::detail::guid_hex(writer) +
                             " (the robot restarted?): filters restarted";
    report().set_error(text);
    runtime::print_line(stderr, text);
    if (estimator_) {
      earlier_counts_ += estimator_->stamp_counters();
    }
    estimator_.reset();  // prepared anew at the next sample (prepare_sized)
    base_estimator_.reset();
    legged_estimator_.reset();
    failed_ = false;
  }

  void estimate(const wbi::msg::SensorSample& sample) {
    const auto& positions = sample.encoder_position();
    if (positions.size() != static_cast<std::size_t>(q_.size())) {
      ++ignored_;  // a sample of the wrong size is not this robot's: never applied
      wrong_size_->set(ignored_);
      return;
    }
    if (base_source_ == BaseSource::legged && !has_legged_inputs(sample)) {
      ++ignored_;  // no IMU or foot F/T reading where the description has them
      wrong_size_->set(ignored_);
      return;
    }
    q_ = Eigen::Map<const Eigen::VectorXd>(positions.data(), q_.size());
    estimator_->update(sample.header().stamp_ns(), q_);
    const auto& tau_in = sample.joint_torque();
    if (tau_in.size() == positions.size()) {
      torque_filter_->update(sample.header().stamp_ns(),
                             Eigen::Map<const Eigen::VectorXd>(tau_in.data(), q_.size()));
      tau_ = torque_filter_->value();
    }
    filter_force_torque(sample);
    publish(sample);
  }

  // The F/T readings, low-passed like the joint torques, into the state's
  // force_torque (sensor frame, in the description's order). A sample without
  // every reading leaves the last estimate.
  void filter_force_torque(const wbi::msg::SensorSample& sample) {
    const auto& readings = sample.force_torque();
    if (!force_torque_filter_ ||
        6 * readings.size() != static_cast<std::size_t>(wrenches_.size())) {
      return;
    }
    for (std::size_t i = 0; i < readings.size(); ++i) {
      const auto& w = readings[i].wrench();
      wrenches_.segment<6>(static_cast<Eigen::Index>(6 * i)) << w.force().x(), w.force().y(),
          w.force().z(), w.torque().x(), w.torque().y(), w.torque().z();
    }
    force_torque_filter_->update(sample.header().stamp_ns(), wrenches_);
    const auto& filtered = force_torque_filter_->value();
    for (std::size_t i = 0; i < readings.size(); ++i) {
      const auto k = static_cast<Eigen::Index>(6 * i);
      auto& out = state_.force_torque()[i];
      out.force().x(filtered[k]);
      out.force().y(filtered[k + 1]);
      out.force().z(filtered[k + 2]);
      out.torque().x(filtered[k + 3]);
      out.torque().y(filtered[k + 4]);
      out.torque().z(filtered[k + 5]);
    }
  }

  void publish(const wbi::msg::SensorSample& sample) {
    auto& state = state_;
    state.header().stamp_ns(sample.header().stamp_ns());
    state.header().seq(sample.header().seq());
    const auto& dq = estimator_->velocity();
    const auto& ddq = estimator_->acceleration();
    for (Eigen::Index j = 0; j < q_.size(); ++j) {
      const auto k = static_cast<std::size_t>(j);
      state.q()[k] = q_[j];
      state.dq()[k] = dq[j];
      state.ddq()[k] = ddq[j];
      state.tau()[k] = tau_[j];
    }
    current_sample_ = &sample;
    fill_base(dq, ddq);
    current_sample_ = nullptr;
    auto counters = earlier_counts_;
    counters += estimator_->stamp_counters();
    state.warnings(static_cast<std::uint32_t>(counters.anomalies()) + ignored_);
    dropped_->set(counters.dropped);
    duplicated_->set(counters.duplicated);
    out_of_order_->set(counters.out_of_order);
    gaps_->set(counters.gaps);
    non_finite_->set(counters.non_finite);
    state_publisher_->publish(state);
  }

  void write_base(const BaseState& base) {
    write_pose(state_.base_pose(), base.world_H_base);
    std::copy(base.velocity.data(), base.velocity.data() + 6, state_.base_velocity().begin());
    std::copy(base.acceleration.data(), base.acceleration.data() + 6,
              state_.base_acceleration().begin());
  }

  bool has_legged_inputs(const wbi::msg::SensorSample& sample) const {
    return static_cast<int>(sample.imus().size()) > imu_index_ &&
           static_cast<int>(sample.force_torque().size()) >= needed_force_torques_;
  }

  ImuInput sample_imu() const {
    const auto& imu = current_sample_->imus()[static_cast<std::size_t>(imu_index_)];
    const auto& o = imu.orientation();
    const auto& w = imu.angular_velocity();
    const auto& a = imu.linear_acceleration();
    ImuInput input;
    input.orientation = Eigen::Quaterniond(o.w(), o.x(), o.y(), o.z());
    input.gyro << w.x(), w.y(), w.z();
    input.accelerometer << a.x(), a.y(), a.z();
    return input;
  }

  // The feet's F/T forces, in the order of the legged estimator's force_frames.
  const Eigen::Matrix3Xd& foot_forces() {
    for (std::size_t i = 0; i < foot_sensor_index_.size(); ++i) {
      const auto index = static_cast<std::size_t>(foot_sensor_index_[i]);
      const auto& f = current_sample_->force_torque()[index].wrench().force();
      foot_forces_.col(static_cast<Eigen::Index>(i)) << f.x(), f.y(), f.z();
    }
    return foot_forces_;
  }

  void fill_base(const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq) {
    auto& state = state_;
    switch (base_source_) {
      case BaseSource::fixed:
        write_pose(state.base_pose(), base_pose_);
        break;
      case BaseSource::fixed_link:
        write_base(base_estimator_->update(q_, dq, ddq));
        break;
      case BaseSource::legged:
        write_base(legged_estimator_->update(current_sample_->header().stamp_ns(), q_, dq, ddq,
                                             sample_imu(), foot_forces()));
        break;
      case BaseSource::topic:
        if (ground_truth_->latest_into(ground_truth_rx_)) {
          state.base_pose(ground_truth_rx_.sample.base_pose());
          state.base_velocity(ground_truth_rx_.sample.base_velocity());
          state.base_acceleration(ground_truth_rx_.sample.base_acceleration());
        }
        break;
    }
  }

  // Runs on a DDS thread: a rejected parameter is reported, never thrown into DDS.
  void on_parameter(const wbi::msg::EstimatorParameter& parameter) {
    try {
      apply_parameter(parameter);
    } catch (const std::exception& e) {
      const std::string text = "estimator of robot '" + robot_ + "': parameter '" +
                               parameter.name().to_string() + "' rejected: " + e.what();
      report().set_error(text);
      runtime::print_line(stderr, text);
    }
  }

  void apply_parameter(const wbi::msg::EstimatorParameter& parameter) {
    std::lock_guard lock(mutex_);
    const std::string name = parameter.name().to_string();
    if (name == "reset") {
      if (estimator_) {
        estimator_->reset();
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

  std::string robot_;
  std::string method_;
  estimation::Parameters method_parameters_;
  double cutoff_hz_ = 0.0;
  BaseSource base_source_ = BaseSource::fixed;
  std::string urdf_;
  std::string fixed_link_;
  Eigen::Matrix4d base_pose_ = Eigen::Matrix4d::Identity();

  std::atomic<bool> active_{false};
  std::mutex mutex_;  // between the sample and the parameter callbacks
  std::unique_ptr<estimation::DerivativeEstimator> estimator_;
  std::optional<estimation::LowPassFilter> torque_filter_;
  std::optional<estimation::LowPassFilter> force_torque_filter_;  // 6 per F/T sensor; none: no F/T
  Eigen::VectorXd wrenches_;  // [6 m] the sample's F/T readings (force, torque)
  std::unique_ptr<FixedLinkBaseEstimator> base_estimator_;
  std::unique_ptr<LeggedBaseEstimator> legged_estimator_;
  LeggedBaseOptions legged_options_;
  std::string imu_sensor_;  // base: legged; empty: the first IMU
  // base: legged; each foot's F/T sensors (none: unmeasured feet)
  std::array<std::vector<std::string>, 2> foot_sensors_;
  int imu_index_ = -1;                  // among the sample's IMU readings
  std::vector<int> foot_sensor_index_;  // among the sample's F/T readings, the left foot's first
  Eigen::Matrix3Xd foot_forces_;        // their forces, one column each
  int needed_force_torques_ = 0;        // F/T readings a sample must have for them
  const wbi::msg::SensorSample* current_sample_ = nullptr;  // while publishing its estimate
  bool have_base_sample_ = false;                           // base: topic
  bool failed_ = false;                            // the description did not fit the base estimator
  std::optional<wbi::msg::SensorSample> pending_;  // a sample that came before the description
  Eigen::VectorXd q_;
  Eigen::VectorXd tau_;
  std::uint32_t ignored_ = 0;
  runtime::StatusCounter* dropped_ = nullptr;  // the report's counters (on_configure)
  runtime::StatusCounter* duplicated_ = nullptr;
  runtime::StatusCounter* out_of_order_ = nullptr;
  runtime::StatusCounter* gaps_ = nullptr;
  runtime::StatusCounter* non_finite_ = nullptr;
  runtime::StatusCounter* wrong_size_ = nullptr;
  runtime::StatusCounter* new_producers_ = nullptr;
  dds::detail::Guid producer_{};              // the writer of the last sensor sample
  estimation::StampCounters earlier_counts_;  // of the filters before a new producer
  wbi::msg::StateEstimate state_;
  dds::Received<wbi::msg::GroundTruth> ground_truth_rx_;

  std::unique_ptr<dds::Subscriber<wbi::msg::RobotDescription>> description_;
  std::unique_ptr<dds::Publisher<wbi::msg::StateEstimate>> state_publisher_;
  std::unique_ptr<dds::Subscriber<wbi::msg::GroundTruth>> ground_truth_;
  std::unique_ptr<dds::Subscriber<wbi::msg::EstimatorParameter>> parameter_subscriber_;
  std::unique_ptr<dds::Subscriber<wbi::msg::SensorSample>> sensors_;
};

}  // namespace

void register_components(runtime::Registry& registry) {
  registry.add<EstimatorComponent>("estimator",
                                   "joint velocity/acceleration, filtered torques and base state "
                                   "from sensor samples");
}

}  // namespace wbi::estimator
