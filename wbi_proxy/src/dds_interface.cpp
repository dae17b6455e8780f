// DdsInterface: the whole-body interface over the robot's DDS topics.
//
// Orders: the controller's joint list C (add_joints) is the order of every
// joint vector of the interface. The robot's order R comes from its
// description; robot_index_[k] is the position in R of controlled joint k,
// resolved once in init(). The local model is built over exactly C, so model
// calls need no mapping; the remote model maps C to the model service's order
// (remote_model.hpp).
#include "wbi/dds_interface.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "joint_claim.hpp"
#include "local_model.hpp"
#include "remote_model.hpp"
#include "size_check.hpp"

namespace wbi::proxy {

namespace {

using Clock = std::chrono::steady_clock;

std::int64_t system_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

wbi::msg::ControlMode to_message(ControlMode mode) {
  switch (mode) {
    case ControlMode::idle:
      return wbi::msg::ControlMode::IDLE;
    case ControlMode::position:
      return wbi::msg::ControlMode::POSITION;
    case ControlMode::position_direct:
      return wbi::msg::ControlMode::POSITION_DIRECT;
    case ControlMode::velocity:
      return wbi::msg::ControlMode::VELOCITY;
    case ControlMode::torque:
      return wbi::msg::ControlMode::TORQUE;
    case ControlMode::pwm:
      return wbi::msg::ControlMode::PWM;
  }
  throw Error("unknown control mode");
}

constexpr std::size_t kSensorKinds = 9;
constexpr std::size_t kEstimateKinds = 8;

std::string seconds_text(double s) { return std::to_string(s) + " s"; }

// What a read of a stream needs: the subscriber, a copy of its newest sample,
// and for blocking reads the count of samples seen at the last read of each kind.
template <class T, std::size_t Kinds>
struct Stream {
  dds::Subscriber<T> subscriber;
  dds::Received<T> received;
  std::array<std::uint64_t, Kinds> seen{};
  std::string what;  // e.g. "sensor samples of robot 'arm' on wbi/arm/sensors"

  Stream(dds::Participant& participant, const std::string& topic, const char* profile,
         std::string description, dds::ProducerPolicy producers)
      : subscriber(participant, topic, profile, nullptr, std::move(producers)),
        what(std::move(description)) {}

  // Brings `received` up to date for a read of `kind`; throws when there is no
  // usable sample.
  const T& take(std::size_t kind, ReadMode mode, double max_age_s,
                std::chrono::milliseconds timeout) {
    if (mode == ReadMode::blocking) {
      if (!subscriber.wait_newer(received, seen[kind], timeout)) {
        throw TimeoutError("no new " + what + " within " +
                           seconds_text(std::chrono::duration<double>(timeout).count()));
      }
    } else if (!subscriber.latest_into(received)) {
      throw StaleDataError("no " + what + " received");
    }
    seen[kind] = received.count;
    const double age = received.age_s();
    if (age > max_age_s) {
      throw StaleDataError(what + ": newest is " + seconds_text(age) + " old (limit " +
                           seconds_text(max_age_s) + ")");
    }
    return received.sample;
  }

  Stamp stamp() const {
    return {received.sample.header().stamp_ns(), received.sample.header().seq(), received.age_s()};
  }
};

class DdsInterface final : public WholeBodyInterface {
 public:
  explicit DdsInterface(const DdsInterfaceOptions& options)
      : options_(options),
        participant_(options.participant),
        description_(participant_, dds::topics::description(options.robot), dds::qos::kLatched,
                     nullptr, dds::ProducerPolicy::one(options.on_producer_event)),
        sensors_(participant_, dds::topics::sensors(options.robot), dds::qos::kStream,
                 "sensor samples of robot '" + options.robot + "' on " +
                     dds::topics::sensors(options.robot),
                 dds::ProducerPolicy::owned_by(dds::description_owner(participant_, description_),
                                               options.on_producer_event)),
        state_(participant_, dds::topics::state(options.robot), dds::qos::kStream,
               "state estimates of robot '" + options.robot + "' on " +
                   dds::topics::state(options.robot),
               dds::ProducerPolicy::one(options.on_producer_event)),
        commands_(participant_, dds::topics::commands(options.robot), dds::qos::kCommand),
        parameters_(participant_, dds::topics::control_parameters(options.robot),
                    dds::qos::kCommand),
        estimator_parameters_(participant_, dds::topics::estimator_parameters(options.robot),
                              dds::qos::kCommand) {
    if (options.model_source == DdsInterfaceOptions::ModelSource::remote) {
      auto remote = std::make_unique<RemoteModel>(participant_, options);
      remote_ = remote.get();
      model_ = std::move(remote);
    }
  }

  // ---- WholeBodyInterface ----

  void add_joints(const IdList& joints) override {
    if (initialized_) {
      throw Error("add_joints() after init(): the controlled joints are fixed by then");
    }
    for (const auto& joint : joints) {
      for (const auto& known : controlled_) {
        if (known == joint) {
          throw Error("joint '" + joint + "' added twice");
        }
      }
      controlled_.push_back(joint);
    }
  }

  void init(std::chrono::milliseconds timeout) override {
    if (initialized_) {
      throw Error("init() called twice");
    }
    if (controlled_.empty()) {
      throw Error("no controlled joints: call add_joints() before init()");
    }
    wait_for_robot(timeout);
    // Blocking reads from now on wait for samples newer than those init() saw.
    sensors_.seen.fill(sensors_.received.count);
    state_.seen.fill(state_.received.count);
    resolve_joints();
    if (options_.claim != DdsInterfaceOptions::Claim::none) {
      claim_ = std::make_unique<JointClaim>(
          participant_, options_.robot, options_.controller, controlled_,
          std::vector<int>(robot_index_.begin(), robot_index_.end()));
      claim_->claim(timeout, options_.claim == DdsInterfaceOptions::Claim::force);
    }
    if (remote_ != nullptr) {
      remote_->bind(controlled_, locked_positions());
    } else {
      model_ = std::make_unique<LocalModel>(options_.urdf, controlled_, locked_positions(),
                                            options_.local_model_backend, options_.armature);
    }
    prepare_messages();
    initialized_ = true;
  }

  void close() override {
    initialized_ = false;
    claim_.reset();  // releases the joints
  }

  // ---- Actuators ----

  void set_control_mode(ControlMode mode) override {
    require_init();
    for (int k = 0; k < dofs(); ++k) {
      switch_mode(k, mode);
    }
    publish_command();
  }

  void set_control_mode(ControlMode mode, int joint) override {
    require_init();
    check_index("joint", joint, dofs());
    switch_mode(joint, mode);
    publish_command();
  }

  void set_control_reference(const ConstVectorRef& reference) override {
    require_init();
    check_size("control reference", reference.size(), dofs());
    references_ = reference;
    publish_command();
  }

  void set_control_reference(double reference, int joint) override {
    require_init();
    check_index("joint", joint, dofs());
    references_[joint] = reference;
    publish_command();
  }

  void set_control_parameter(ControlParameter parameter, const ConstVectorRef& values) override {
    require_init();
    check_size("control parameter values", values.size(), dofs());
    for (int k = 0; k < dofs(); ++k) {
      parameter_values(parameter)[static_cast<std::size_t>(k)] = values[k];
    }
    publish_parameters(parameter);
  }

  void set_control_parameter(ControlParameter parameter, double value, int joint) override {
    require_init();
    check_index("joint", joint, dofs());
    auto& values = parameter_values(parameter);
    for (auto& v : values) {
      v = std::numeric_limits<double>::quiet_NaN();  // NaN: leave this joint as it is
    }
    values[static_cast<std::size_t>(joint)] = value;
    publish_parameters(parameter);
  }

  // ---- Sensors ----

  const IdList& sensor_list(SensorKind kind) const override {
    switch (kind) {
      case SensorKind::imu:
      case SensorKind::accelerometer:
      case SensorKind::gyroscope:
        return imu_names_;
      case SensorKind::force_torque:
        return force_torque_names_;
      default:
        return controlled_;
    }
  }

  Stamp read_sensors(SensorKind kind, VectorRef values, ReadMode mode) override {
    require_init();
    const int count = static_cast<int>(sensor_list(kind).size());
    check_size("sensor values", values.size(), count * sensor_width(kind));
    return read_sensor_range(kind, 0, count, values, mode);
  }

  Stamp read_sensor(SensorKind kind, int index, VectorRef values, ReadMode mode) override {
    require_init();
    check_index("sensor", index, static_cast<int>(sensor_list(kind).size()));
    check_size("sensor values", values.size(), sensor_width(kind));
    return read_sensor_range(kind, index, 1, values, mode);
  }

  // ---- State ----

  Stamp read_estimates(EstimateKind kind, VectorRef values, ReadMode mode) override {
    require_init();
    const int count = estimate_count(kind);
    check_size("estimate values", values.size(), count * estimate_width(kind));
    return read_estimate_range(kind, 0, count, values, mode);
  }

  Stamp read_estimate(EstimateKind kind, int index, VectorRef values, ReadMode mode) override {
    require_init();
    check_index("estimate", index, estimate_count(kind));
    check_size("estimate values", values.size(), estimate_width(kind));
    return read_estimate_range(kind, index, 1, values, mode);
  }

  Stamp read_base_pose(Transform& world_H_base, ReadMode mode) override {
    require_init();
    const auto& pose = take_state(EstimateKind::base_pose, mode).base_pose();
    const Eigen::Quaterniond orientation(pose.orientation().w(), pose.orientation().x(),
                                         pose.orientation().y(), pose.orientation().z());
    world_H_base.setIdentity();
    world_H_base.topLeftCorner<3, 3>() = orientation.normalized().toRotationMatrix();
    world_H_base.topRightCorner<3, 1>() << pose.position().x(), pose.position().y(),
        pose.position().z();
    return state_.stamp();
  }

  // Sent to the estimator on wbi/<robot>/state/parameters; "fixed_link" takes
  // the link's index in frame_list().
  void set_estimation_parameter(const std::string& name, double value) override {
    require_init();
    wbi::msg::EstimatorParameter parameter;
    parameter.header().robot(options_.robot);
    parameter.header().stamp_ns(system_now_ns());
    parameter.name(name);
    parameter.value(value);
    if (name == "fixed_link") {
      const int frame = static_cast<int>(value);
      check_index("fixed_link frame", frame, static_cast<int>(frame_list().size()));
      parameter.text(frame_list()[static_cast<std::size_t>(frame)]);
    }
    if (!estimator_parameters_.publish(parameter)) {
      throw Error("estimator parameter '" + name + "' for robot '" + options_.robot + "' not sent");
    }
  }

  // ---- Model ----

  int dofs() const override { return static_cast<int>(controlled_.size()); }
  const IdList& joint_list() const override { return controlled_; }
  JointLimits joint_limits(int joint) const override { return model().joint_limits(joint); }
  const IdList& frame_list() const override { return model().frame_list(); }
  int frame_index(const std::string& frame) const override { return model().frame_index(frame); }

  void frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                  Transform& world_H_frame) override {
    model().frame_pose(q, world_H_base, frame, world_H_frame);
  }
  void jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                MatrixRef J) override {
    model().jacobian(q, world_H_base, frame, J);
  }
  void dj_nu(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
             const ConstVectorRef& base_velocity, int frame, VectorRef out) override {
    model().dj_nu(q, world_H_base, dq, base_velocity, frame, out);
  }
  void mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) override {
    model().mass_matrix(q, world_H_base, M);
  }
  void bias_forces(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
                   const ConstVectorRef& base_velocity, const Eigen::Vector3d& gravity,
                   VectorRef h) override {
    model().bias_forces(q, world_H_base, dq, base_velocity, gravity, h);
  }
  void gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                      const Eigen::Vector3d& gravity, VectorRef g) override {
    model().gravity_forces(q, world_H_base, gravity, g);
  }
  void inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                        const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                        const ConstVectorRef& ddq, const ConstVectorRef& base_acceleration,
                        const Eigen::Vector3d& gravity, VectorRef tau) override {
    model().inverse_dynamics(q, world_H_base, dq, base_velocity, ddq, base_acceleration, gravity,
                             tau);
  }
  void centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                           const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                           VectorRef momentum) override {
    model().centroidal_momentum(q, world_H_base, dq, base_velocity, momentum);
  }
  void centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                  MatrixRef A) override {
    model().centroidal_momentum_matrix(q, world_H_base, A);
  }
  void com(const ConstVectorRef& q, const Transform& world_H_base, Eigen::Vector3d& out) override {
    model().com(q, world_H_base, out);
  }
  void com_jacobian(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef J) override {
    model().com_jacobian(q, world_H_base, J);
  }

 private:
  void require_init() const {
    if (!initialized_) {
      throw Error("the whole-body interface of robot '" + options_.robot +
                  "' is not initialized: call init() first");
    }
  }

  wbi::Model& model() {
    require_init();
    return *model_;
  }
  const wbi::Model& model() const {
    require_init();
    return *model_;
  }

  // Waits for every component the interface needs; names all that are missing.
  void wait_for_robot(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    const auto remaining = [&] {
      return std::max(Clock::duration::zero(), deadline - Clock::now());
    };
    std::vector<std::string> missing;
    if (!description_.wait_newer(description_rx_, 0, remaining())) {
      missing.push_back("the robot description on " + dds::topics::description(options_.robot) +
                        " (sensor component)");
    }
    if (!sensors_.subscriber.wait_newer(sensors_.received, 0, remaining())) {
      missing.push_back("sensor samples on " + dds::topics::sensors(options_.robot) +
                        " (sensor component)");
    }
    if (!state_.subscriber.wait_newer(state_.received, 0, remaining())) {
      missing.push_back("state estimates on " + dds::topics::state(options_.robot) +
                        " (estimator)");
    }
    if (!commands_.wait_for_subscribers(1, remaining())) {
      missing.push_back("a reader of " + dds::topics::commands(options_.robot) +
                        " (actuator component)");
    }
    if (remote_ != nullptr) {
      const std::string model_missing = remote_->wait_ready(deadline);
      if (!model_missing.empty()) {
        missing.push_back(model_missing);
      }
    }
    if (!missing.empty()) {
      std::string text = "robot '" + options_.robot + "' not ready within " +
                         seconds_text(std::chrono::duration<double>(timeout).count()) +
                         "; missing: ";
      for (std::size_t i = 0; i < missing.size(); ++i) {
        text += (i == 0 ? "" : "; ") + missing[i];
      }
      throw TimeoutError(text);
    }
  }

  void resolve_joints() {
    const auto& description = description_rx_.sample;
    const auto& names = description.joint_names();
    robot_index_.clear();
    for (const auto& joint : controlled_) {
      std::optional<std::size_t> found;
      for (std::size_t r = 0; r < names.size(); ++r) {
        if (names[r] == joint) {
          found = r;
        }
      }
      if (!found) {
        std::string known;
        for (const auto& name : names) {
          known += (known.empty() ? "" : ", ") + name.to_string();
        }
        throw Error("joint '" + joint + "' is not a joint of robot '" + options_.robot +
                    "' (its joints: " + known + ")");
      }
      robot_index_.push_back(static_cast<std::uint16_t>(*found));
    }
    imu_names_.clear();
    force_torque_names_.clear();
    for (const auto& sensor : description.sensors()) {
      if (sensor.kind() == wbi::msg::SensorKind::IMU) {
        imu_names_.push_back(sensor.name().to_string());
      } else if (sensor.kind() == wbi::msg::SensorKind::FORCE_TORQUE) {
        force_torque_names_.push_back(sensor.name().to_string());
      }
    }
  }

  // Joints of the robot outside the controlled list: from the options, else
  // where the first sensor sample measured them.
  std::map<std::string, double> locked_positions() const {
    std::map<std::string, double> locked = options_.locked_positions;
    const auto& names = description_rx_.sample.joint_names();
    const auto& measured = sensors_.received.sample.encoder_position();
    for (std::size_t r = 0; r < names.size() && r < measured.size(); ++r) {
      const std::string name = names[r].to_string();
      bool controlled = false;
      for (const auto& joint : controlled_) {
        controlled = controlled || joint == name;
      }
      if (!controlled && locked.count(name) == 0) {
        locked[name] = measured[r];
      }
    }
    return locked;
  }

  void prepare_messages() {
    const auto n = static_cast<std::size_t>(dofs());
    modes_.assign(n, ControlMode::idle);
    references_ = Eigen::VectorXd::Zero(dofs());
    command_.header().robot(options_.robot);
    command_.controller(options_.controller);
    command_.joints(robot_index_);
    command_.modes().assign(n, wbi::msg::ControlMode::IDLE);
    command_.references().assign(n, 0.0);
    parameters_msg_.header().robot(options_.robot);
    parameters_msg_.controller(options_.controller);
    parameters_msg_.joints(robot_index_);
    const double unchanged = std::numeric_limits<double>::quiet_NaN();
    for (auto* values : {&parameters_msg_.kp(), &parameters_msg_.ki(), &parameters_msg_.kd(),
                         &parameters_msg_.reference_speed()}) {
      values->assign(n, unchanged);
    }
  }

  void switch_mode(int joint, ControlMode mode) {
    modes_[static_cast<std::size_t>(joint)] = mode;
    if (mode == ControlMode::position || mode == ControlMode::position_direct) {
      const auto& sample =
          sensors_.take(0, ReadMode::latest, options_.max_age_s, options_.blocking_read_timeout);
      references_[joint] =
          sample.encoder_position().at(robot_index_[static_cast<std::size_t>(joint)]);
    } else {
      references_[joint] = 0.0;
    }
  }

  void publish_command() {
    if (claim_) {
      claim_->check();  // throws once another controller took a joint
    }
    auto& header = command_.header();
    header.stamp_ns(system_now_ns());
    header.seq(command_seq_++);
    // Lockstep: the tick this command answers is the newest sample the controller read
    // (sensor and state samples carry the robot's tick as their sequence number).
    command_.tick(
        std::max(sensors_.received.sample.header().seq(), state_.received.sample.header().seq()));
    // Latency: the sensor sample this command was computed from (a state
    // estimate carries its sensor sample's stamp).
    command_.source_stamp_ns(std::max(sensors_.received.sample.header().stamp_ns(),
                                      state_.received.sample.header().stamp_ns()));
    for (std::size_t k = 0; k < modes_.size(); ++k) {
      command_.modes()[k] = to_message(modes_[k]);
      command_.references()[k] = references_[static_cast<Eigen::Index>(k)];
    }
    if (!commands_.publish(command_)) {
      throw Error("command to robot '" + options_.robot + "' not sent");
    }
  }

  std::vector<double>& parameter_values(ControlParameter parameter) {
    switch (parameter) {
      case ControlParameter::kp:
        return parameters_msg_.kp();
      case ControlParameter::ki:
        return parameters_msg_.ki();
      case ControlParameter::kd:
        return parameters_msg_.kd();
      case ControlParameter::reference_speed:
        return parameters_msg_.reference_speed();
    }
    throw Error("unknown control parameter");
  }

  // Publishes one parameter; the others travel as NaN (unchanged).
  void publish_parameters(ControlParameter parameter) {
    const double unchanged = std::numeric_limits<double>::quiet_NaN();
    for (auto other : {ControlParameter::kp, ControlParameter::ki, ControlParameter::kd,
                       ControlParameter::reference_speed}) {
      if (other != parameter) {
        for (auto& v : parameter_values(other)) {
          v = unchanged;
        }
      }
    }
    if (claim_) {
      claim_->check();
    }
    parameters_msg_.header().stamp_ns(system_now_ns());
    parameters_msg_.header().seq(parameters_seq_++);
    if (!parameters_.publish(parameters_msg_)) {
      throw Error("control parameters for robot '" + options_.robot + "' not sent");
    }
  }

  // Joint values in robot order → the controlled joints [first, first + count).
  void gather(const std::vector<double>& robot_values, int first, int count, VectorRef out,
              const char* what) const {
    for (int k = 0; k < count; ++k) {
      const auto r = robot_index_[static_cast<std::size_t>(first + k)];
      if (r >= robot_values.size()) {
        throw Error(std::string("robot '") + options_.robot + "' sends no " + what);
      }
      out[k] = robot_values[r];
    }
  }

  Stamp read_sensor_range(SensorKind kind, int first, int count, VectorRef out, ReadMode mode) {
    const auto index = static_cast<std::size_t>(kind);
    if (kind == SensorKind::encoder_velocity || kind == SensorKind::encoder_acceleration) {
      // No speed sensors on the wire: the estimator's values stand in for them.
      const auto& state =
          state_.take(index, mode, options_.max_age_s, options_.blocking_read_timeout);
      gather(kind == SensorKind::encoder_velocity ? state.dq() : state.ddq(), first, count, out,
             kind == SensorKind::encoder_velocity ? "joint velocities" : "joint accelerations");
      return state_.stamp();
    }
    const auto& sample =
        sensors_.take(index, mode, options_.max_age_s, options_.blocking_read_timeout);
    switch (kind) {
      case SensorKind::encoder_position:
        gather(sample.encoder_position(), first, count, out, "encoder positions");
        break;
      case SensorKind::joint_torque:
        gather(sample.joint_torque(), first, count, out, "joint torques");
        break;
      case SensorKind::motor_pwm:
        gather(sample.motor_pwm(), first, count, out, "motor PWM");
        break;
      case SensorKind::force_torque:
        for (int i = 0; i < count; ++i) {
          const auto& w = sample.force_torque().at(static_cast<std::size_t>(first + i)).wrench();
          out.segment<6>(6 * i) << w.force().x(), w.force().y(), w.force().z(), w.torque().x(),
              w.torque().y(), w.torque().z();
        }
        break;
      default:  // imu, accelerometer, gyroscope
        for (int i = 0; i < count; ++i) {
          const auto& imu = sample.imus().at(static_cast<std::size_t>(first + i));
          const auto& o = imu.orientation();
          const auto& w = imu.angular_velocity();
          const auto& a = imu.linear_acceleration();
          if (kind == SensorKind::imu) {
            out.segment<10>(10 * i) << o.w(), o.x(), o.y(), o.z(), w.x(), w.y(), w.z(), a.x(),
                a.y(), a.z();
          } else if (kind == SensorKind::gyroscope) {
            out.segment<3>(3 * i) << w.x(), w.y(), w.z();
          } else {
            out.segment<3>(3 * i) << a.x(), a.y(), a.z();
          }
        }
    }
    return sensors_.stamp();
  }

  int estimate_count(EstimateKind kind) const {
    switch (kind) {
      case EstimateKind::base_pose:
      case EstimateKind::base_velocity:
      case EstimateKind::base_acceleration:
        return 1;
      case EstimateKind::force_torque:
        return static_cast<int>(force_torque_names_.size());
      default:
        return dofs();
    }
  }

  const wbi::msg::StateEstimate& take_state(EstimateKind kind, ReadMode mode) {
    return state_.take(static_cast<std::size_t>(kind), mode, options_.max_age_s,
                       options_.blocking_read_timeout);
  }

  Stamp read_estimate_range(EstimateKind kind, int first, int count, VectorRef out, ReadMode mode) {
    const auto& state = take_state(kind, mode);
    switch (kind) {
      case EstimateKind::joint_position:
        gather(state.q(), first, count, out, "joint position estimates");
        break;
      case EstimateKind::joint_velocity:
        gather(state.dq(), first, count, out, "joint velocity estimates");
        break;
      case EstimateKind::joint_acceleration:
        gather(state.ddq(), first, count, out, "joint acceleration estimates");
        break;
      case EstimateKind::joint_torque:
        gather(state.tau(), first, count, out, "joint torque estimates");
        break;
      case EstimateKind::base_pose: {
        const auto& p = state.base_pose();
        out << p.position().x(), p.position().y(), p.position().z(), p.orientation().w(),
            p.orientation().x(), p.orientation().y(), p.orientation().z();
        break;
      }
      case EstimateKind::base_velocity:
        out = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(state.base_velocity().data());
        break;
      case EstimateKind::base_acceleration:
        out = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(state.base_acceleration().data());
        break;
      case EstimateKind::force_torque:
        if (state.force_torque().size() < static_cast<std::size_t>(first + count)) {
          throw Error("force_torque estimates: the state of robot '" + options_.robot +
                      "' carries " + std::to_string(state.force_torque().size()) + " of its " +
                      std::to_string(force_torque_names_.size()) +
                      " F/T sensors (the estimator component fills them from the sensor "
                      "samples; read_sensors(force_torque) has the raw readings)");
        }
        for (int i = 0; i < count; ++i) {
          const auto& w = state.force_torque().at(static_cast<std::size_t>(first + i));
          out.segment<6>(6 * i) << w.force().x(), w.force().y(), w.force().z(), w.torque().x(),
              w.torque().y(), w.torque().z();
        }
        break;
    }
    return state_.stamp();
  }

  DdsInterfaceOptions options_;
  dds::Participant participant_;
  dds::Subscriber<wbi::msg::RobotDescription> description_;
  dds::Received<wbi::msg::RobotDescription> description_rx_;
  Stream<wbi::msg::SensorSample, kSensorKinds> sensors_;
  Stream<wbi::msg::StateEstimate, kEstimateKinds> state_;
  dds::Publisher<wbi::msg::ActuatorCommand> commands_;
  dds::Publisher<wbi::msg::ControlParameters> parameters_;
  dds::Publisher<wbi::msg::EstimatorParameter> estimator_parameters_;

  IdList controlled_;
  std::unique_ptr<JointClaim> claim_;  // after init(), unless options_.claim is none
  bool initialized_ = false;
  std::vector<std::uint16_t>
      robot_index_;  // [dofs] position of controlled joint k in the robot's order
  IdList imu_names_;
  IdList force_torque_names_;
  std::unique_ptr<wbi::Model> model_;  // LocalModel, or RemoteModel from construction on
                                       // (DdsInterfaceOptions::model_source)
  RemoteModel* remote_ = nullptr;      // model_ when the model is remote

  std::vector<ControlMode> modes_;  // [dofs] current mode per controlled joint
  Eigen::VectorXd references_;      // [dofs] current reference per controlled joint
  wbi::msg::ActuatorCommand command_;
  wbi::msg::ControlParameters parameters_msg_;
  std::uint64_t command_seq_ = 0;
  std::uint64_t parameters_seq_ = 0;
};

}  // namespace

}  // namespace wbi::proxy

namespace wbi {

std::optional<DdsInterfaceOptions::Claim> claim_from_text(std::string_view text) {
  using Claim = DdsInterfaceOptions::Claim;
  if (text == "claim") {
    return Claim::claim;
  }
  if (text == "force") {
    return Claim::force;
  }
  if (text == "none") {
    return Claim::none;
  }
  return std::nullopt;
}

std::unique_ptr<WholeBodyInterface> make_dds_interface(const DdsInterfaceOptions& options) {
  if (options.robot.empty()) {
    throw Error("DdsInterfaceOptions.robot is empty: name the robot whose topics to use");
  }
  if (options.model_source == DdsInterfaceOptions::ModelSource::local && options.urdf.empty()) {
    throw Error("DdsInterfaceOptions.urdf is empty: a local model needs the robot's URDF");
  }
  if (options.model_source == DdsInterfaceOptions::ModelSource::remote &&
      options.model_timeout.count() <= 0) {
    throw Error("DdsInterfaceOptions.model_timeout must be > 0 for a remote model");
  }
  if (!(options.max_age_s > 0.0)) {
    throw Error("DdsInterfaceOptions.max_age_s must be > 0");
  }
  return std::make_unique<proxy::DdsInterface>(options);
}

}  // namespace wbi
