// The estimator component's work per sensor sample: waiting for its inputs,
// estimating joints, F/T and base state, and publishing the StateEstimate.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <string_view>

#include <wbi/dds/topics.hpp>
#include <wbi/msg/eigen.hpp>
#include <wbi/msg/wire_vocabulary.hpp>
#include <wbi/runtime/console_line.hpp>

#include "estimator_component_impl.hpp"

namespace wbi::estimator {

using wbi::msg::to_eigen;
using wbi::msg::to_wire;

namespace detail {

// A sample that came before activation or before the description is kept and
// estimated once both are there: a lockstep robot sends its next sample only
// after this one has been answered.
void EstimatorComponent::on_description() {
  std::lock_guard lock(mutex_);
  process_pending();
}

void EstimatorComponent::on_base_sample(std::uint64_t seq) {
  std::lock_guard lock(mutex_);
  have_base_sample_ = true;
  ground_truth_seq_ = static_cast<std::int64_t>(seq);
  ground_truth_waived_ = false;
  process_pending();
  if (has_deferred_ && inputs_in(deferred_.header().seq())) {
    estimate_deferred(false);
  }
}

// Inputs of a tick. The sensor sample of tick k and the inputs estimated with
// it come on readers of their own, in an order DDS timing decides. Taking
// whatever had come made a lockstep run's result depend on it (the command a
// sample met could be a tick late: two runs of one deploy file differed). So
// sample k waits for its own: the robot's ground truth of tick k (base:
// topic), and the command of every lockstep controller answering tick k − 1,
// the one the robot applied before stepping to k (accelerations: model). A
// sample whose inputs have not all come is deferred, estimated on the thread
// of the input that completes it, or after lockstep_timeout_s (counted in
// samples_with_late_inputs; the missing input is not waited for again until
// it comes). In lockstep nothing newer than the inputs of tick k can come
// before state k is published, so the estimate depends on the tick only.
bool EstimatorComponent::inputs_in(std::uint64_t seq) const {
  const auto k = static_cast<std::int64_t>(seq);
  if (match_ground_truth_ && !ground_truth_waived_ && ground_truth_seq_ < k) {
    return false;
  }
  for (std::size_t i = 0; i < answered_.size(); ++i) {
    if (waived_[i] == 0 && answered_[i] < k - 1) {
      return false;
    }
  }
  return true;
}

void EstimatorComponent::on_command(const wbi::msg::ActuatorCommand& command) {
  std::lock_guard lock(mutex_);
  if (model_acceleration_) {
    model_acceleration_->on_command(command);
  }
  if (command.tick() == wbi::msg::kNoTick) {
    return;  // a mode switch answers no tick (docs/conventions.md)
  }
  const std::string_view sender(command.controller().c_str(), command.controller().size());
  for (std::size_t i = 0; i < lockstep_controllers_.size(); ++i) {
    if (lockstep_controllers_[i] == sender) {
      answered_[i] = std::max(answered_[i], static_cast<std::int64_t>(command.tick()));
      waived_[i] = 0;
    }
  }
  if (has_deferred_ && inputs_in(deferred_.header().seq())) {
    estimate_deferred(false);
  }
}

void EstimatorComponent::defer(const wbi::msg::SensorSample& sample) {
  deferred_ = sample;  // reuses its buffers once sized: no allocation
  has_deferred_ = true;
  deferred_until_ = std::chrono::steady_clock::now() + inputs_timeout_;
  deferred_changed_.notify_all();
}

void EstimatorComponent::estimate_deferred(bool timed_out) {
  has_deferred_ = false;
  if (timed_out) {
    const auto k = static_cast<std::int64_t>(deferred_.header().seq());
    if (match_ground_truth_ && ground_truth_seq_ < k) {
      ground_truth_waived_ = true;
    }
    for (std::size_t i = 0; i < answered_.size(); ++i) {
      waived_[i] = answered_[i] < k - 1 ? 1 : waived_[i];
    }
    if (late_inputs_->value() == 0) {  // the first one: allocates, once
      const std::string text = "estimator of robot '" + robot_ + "': sample " + std::to_string(k) +
                               " estimated without all its inputs (ground truth of its tick, "
                               "lockstep controllers' commands of the tick before) after "
                               "lockstep_timeout_s";
      report().set_error(text);
      runtime::print_line(stderr, text);
    }
    late_inputs_->add();
  }
  estimate(deferred_);
}

void EstimatorComponent::run_deferred() {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    if (!has_deferred_) {
      deferred_changed_.wait(lock);
    } else if (deferred_changed_.wait_until(lock, deferred_until_) == std::cv_status::timeout &&
               has_deferred_ && std::chrono::steady_clock::now() >= deferred_until_) {
      estimate_deferred(true);
    }
  }
}

void EstimatorComponent::stop_deferred() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  deferred_changed_.notify_all();
  if (deferred_thread_.joinable()) {
    deferred_thread_.join();
  }
}

// Every input of an estimate is there: active, the description, the base sample (topic).
bool EstimatorComponent::ready(std::size_t joints) {
  return active_ && (base_source_ != BaseSource::topic || have_base_sample_) &&
         (estimator_ || prepare(joints));
}

void EstimatorComponent::process_pending() {  // caller holds mutex_
  if (pending_ && ready(pending_->encoder_position().size())) {
    estimate(*pending_);
    pending_.reset();
  }
}

void EstimatorComponent::on_sample(const wbi::msg::SensorSample& sample,
                                   const dds::detail::Guid& writer) {
  std::lock_guard lock(mutex_);
  if (writer != producer_) {
    on_new_producer(writer);
  }
  if (!ready(sample.encoder_position().size())) {
    pending_ = sample;  // start-up only: not active, no description or no base sample yet
    return;
  }
  if (has_deferred_) {
    estimate_deferred(true);  // a newer sample: the robot stepped on without those inputs
  }
  if (!inputs_in(sample.header().seq())) {
    defer(sample);
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
void EstimatorComponent::on_new_producer(const dds::detail::Guid& writer) {  // caller holds mutex_
  const bool first = producer_ == dds::detail::Guid{};
  producer_ = writer;
  if (first) {
    return;
  }
  new_producers_->add();
  has_deferred_ = false;                              // the old robot's tick
  std::fill(answered_.begin(), answered_.end(), -1);  // the new robot's ticks start again
  const std::string text = "estimator of robot '" + robot_ + "': sensor samples from a new " +
                           "writer " + dds::detail::guid_hex(writer) +
                           " (the robot restarted?): filters restarted";
  report().set_error(text);
  runtime::print_line(stderr, text);
  events().emit(EventSeverity::warning, EventKind::producer_restarted, text,
                dds::topics::sensors(robot_));
  if (estimator_) {
    earlier_counts_ += estimator_->stamp_counters();
  }
  estimator_.reset();  // prepared anew at the next sample (prepare_sized)
  base_estimator_.reset();
  legged_estimator_.reset();
  failed_ = false;
}

void EstimatorComponent::estimate(const wbi::msg::SensorSample& sample) {
  const auto start = std::chrono::steady_clock::now();
  const auto& positions = sample.encoder_position();
  if (positions.size() != joints_) {
    ++ignored_;  // a sample of the wrong size is not this robot's: never applied
    wrong_size_->set(ignored_);
    return;
  }
  if (base_source_ == BaseSource::legged && !has_legged_inputs(sample)) {
    ++ignored_;  // no IMU or foot F/T reading where the description has them
    wrong_size_->set(ignored_);
    return;
  }
  current_sample_ = &sample;
  const auto q = sample_q();
  estimator_->update(sample.header().stamp_ns(), q);
  if (model_ddq_) {
    sample_used_ = estimation::used(model_ddq_->update(sample.header().stamp_ns(), q));
  }
  // Joint torques: none when the array is empty (tau stays 0); a joint without
  // a sensor (NaN on the wire, idl/sensors.idl) enters as 0.
  const auto& tau_in = sample.joint_torque();
  if (!torque_estimation_ && tau_in.size() == positions.size()) {
    for (Eigen::Index j = 0; j < tau_in_.size(); ++j) {
      tau_in_[j] =
          torque_sensor_[static_cast<std::size_t>(j)] ? tau_in[static_cast<std::size_t>(j)] : 0.0;
    }
    torque_filter_->update(sample.header().stamp_ns(), tau_in_);
    tau_ = torque_filter_->value();
  }
  filter_force_torque(sample);
  fill_state(sample);
  current_sample_ = nullptr;
  estimate_times_.add(std::chrono::steady_clock::now() - start);
  state_publisher_->publish(state_);
}

// The F/T readings, low-passed like the joint torques, into the state's
// force_torque (sensor frame, in the description's order). A sample without
// every reading leaves the last estimate.
void EstimatorComponent::filter_force_torque(const wbi::msg::SensorSample& sample) {
  const auto& readings = sample.force_torque();
  if (!force_torque_filter_ || 6 * readings.size() != static_cast<std::size_t>(wrenches_.size())) {
    return;
  }
  for (std::size_t i = 0; i < readings.size(); ++i) {
    to_eigen(readings[i].wrench(), wrenches_.segment<6>(static_cast<Eigen::Index>(6 * i)));
  }
  force_torque_filter_->update(sample.header().stamp_ns(), wrenches_);
  const auto& filtered = force_torque_filter_->value();
  for (std::size_t i = 0; i < readings.size(); ++i) {
    to_wire(filtered.segment<6>(static_cast<Eigen::Index>(6 * i)), state_.force_torque()[i]);
  }
}

void EstimatorComponent::fill_state(const wbi::msg::SensorSample& sample) {
  auto& state = state_;
  state.header().stamp_ns(sample.header().stamp_ns());
  state.header().seq(sample.header().seq());
  const auto& dq = estimator_->velocity();
  const auto& ddq = estimator_->acceleration();
  state.q() = sample.encoder_position();  // sized alike: copied in place, no allocation
  to_wire(dq, state.dq());
  to_wire(ddq, state.ddq());
  fill_base(dq, ddq);
  estimate_torques(dq, ddq);
  feed_model_acceleration();
  to_wire(tau_, state.tau());
  auto counters = earlier_counts_;
  counters += estimator_->stamp_counters();
  state.warnings(static_cast<std::uint32_t>(counters.anomalies()) + ignored_);
  dropped_->set(counters.dropped);
  duplicated_->set(counters.duplicated);
  out_of_order_->set(counters.out_of_order);
  gaps_->set(counters.gaps);
  non_finite_->set(counters.non_finite);
}

// joint_torques: force_torque — the torques through the model from the F/T
// readings, at the state's base (fill_base first), low-passed like sensed ones.
void EstimatorComponent::estimate_torques(const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq) {
  if (!torque_estimation_) {
    return;
  }
  if (!torque_estimation_->update(*current_sample_, sample_q(), dq, ddq, state_)) {
    if (missing_force_torque_->value() == 0) {  // the first one: allocates, once
      const std::string text = "estimator of robot '" + robot_ +
                               "': " + torque_estimation_->missing_readings(*current_sample_);
      report().set_error(text);
      runtime::print_line(stderr, text);
    }
    missing_force_torque_->add();  // the last torques and wrenches are kept
    return;
  }
  if (torque_estimation_->invalid_joints() > 0 || torque_estimation_->invalid_wrenches() > 0) {
    invalid_torque_estimates_->add();
  }
  torque_filter_->update(current_sample_->header().stamp_ns(), torque_estimation_->torques());
  tau_ = torque_filter_->value();
  torque_estimation_->write_wrenches(state_);
}

// accelerations: model — the model's accelerations at this sample (its base
// and external wrenches estimated above) enter their filter, whose estimate
// replaces the method's ddq in the state. Without them (a joint without a
// torque command) the method's ddq stays. The base estimators and the torque
// estimation used the method's. The model takes that filter's velocity: it
// tells stuck joints (below stick_velocity) better than a noisier method's
// (iCub 3: 0.28 rad/s² of q̈ error with it, 1.06 with backward differences).
void EstimatorComponent::feed_model_acceleration() {
  if (!model_ddq_ || !sample_used_) {
    return;
  }
  if (!model_acceleration_->compute(sample_q(), model_ddq_->velocity(), state_, ddq_model_)) {
    if (without_model_acceleration_->value() == 0) {  // the first one: allocates, once
      const std::string text = "estimator of robot '" + robot_ +
                               "': accelerations: model: no torque command for " +
                               model_acceleration_->joints_without_torque() +
                               " (the model's acceleration needs every joint's torque); the "
                               "method's acceleration is published meanwhile";
      report().set_error(text);
      runtime::print_line(stderr, text);
    }
    without_model_acceleration_->add();
    return;
  }
  model_ddq_->set_model_acceleration(ddq_model_);
  const auto& ddq = model_ddq_->acceleration();
  to_wire(ddq, state_.ddq());
}

void EstimatorComponent::write_base(const BaseState& base) {
  to_wire(base.world_H_base, state_.base_pose());
  to_wire(base.velocity, state_.base_velocity());
  to_wire(base.acceleration, state_.base_acceleration());
}

bool EstimatorComponent::has_legged_inputs(const wbi::msg::SensorSample& sample) const {
  return static_cast<int>(sample.imus().size()) > imu_index_ &&
         static_cast<int>(sample.force_torque().size()) >= needed_force_torques_;
}

Eigen::Map<const Eigen::VectorXd> EstimatorComponent::sample_q() const {
  return wbi::msg::view(current_sample_->encoder_position());
}

ImuInput EstimatorComponent::sample_imu() const {
  const auto& imu = current_sample_->imus()[static_cast<std::size_t>(imu_index_)];
  ImuInput input;
  input.orientation = to_eigen(imu.orientation());
  input.gyro = to_eigen(imu.angular_velocity());
  input.accelerometer = to_eigen(imu.linear_acceleration());
  return input;
}

// The feet's F/T forces, in the order of the legged estimator's force_frames.
const Eigen::Matrix3Xd& EstimatorComponent::foot_forces() {
  for (std::size_t i = 0; i < foot_sensor_index_.size(); ++i) {
    const auto index = static_cast<std::size_t>(foot_sensor_index_[i]);
    foot_forces_.col(static_cast<Eigen::Index>(i)) =
        to_eigen(current_sample_->force_torque()[index].wrench().force());
  }
  return foot_forces_;
}

void EstimatorComponent::fill_base(const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq) {
  auto& state = state_;
  switch (base_source_) {
    case BaseSource::fixed:
      to_wire(base_pose_, state.base_pose());
      break;
    case BaseSource::fixed_link:
      write_base(base_estimator_->update(sample_q(), dq, ddq));
      break;
    case BaseSource::legged:
      write_base(legged_estimator_->update(current_sample_->header().stamp_ns(), sample_q(), dq,
                                           ddq, sample_imu(), foot_forces()));
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

}  // namespace detail

}  // namespace wbi::estimator
