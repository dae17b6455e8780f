#include "lab_posture_planner.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <wbi/controllers/interface_options.hpp>
#include <wbi/controllers/reference_writer.hpp>
#include <wbi/dds_interface.hpp>

namespace lab {

namespace {

std::chrono::milliseconds milliseconds(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000.0));
}

// A per-joint vector parameter: `joints` values, else an error naming the key.
Eigen::VectorXd per_joint(const wbi::runtime::Parameters& parameters, const std::string& key,
                          std::vector<double> values, int joints) {
  if (static_cast<int>(values.size()) != joints) {
    throw wbi::runtime::ParameterError(parameters.where(key) + ": " + key + " takes " +
                                       std::to_string(joints) + " values (one per joint), got " +
                                       std::to_string(values.size()));
  }
  return Eigen::Map<const Eigen::VectorXd>(values.data(), joints);
}

}  // namespace

LabPosturePlanner::LabPosturePlanner() = default;
LabPosturePlanner::~LabPosturePlanner() = default;

void LabPosturePlanner::read_trajectory(const wbi::runtime::Parameters& parameters, int joints) {
  PostureTrajectory& p = trajectory_;
  p.target =
      per_joint(parameters, "target", parameters.require<std::vector<double>>("target"), joints);
  p.sway = per_joint(parameters, "sway_amplitude",
                     parameters.get<std::vector<double>>(
                         "sway_amplitude", std::vector<double>(static_cast<std::size_t>(joints))),
                     joints);
  p.from = p.target;  // until the first state
  p.start_s = parameters.get<double>("start_s", p.start_s);
  p.move_s = parameters.get<double>("move_s", p.move_s);
  p.sway_hz = parameters.get<double>("sway_frequency_hz", p.sway_hz);
  p.sway_periods = parameters.get<int>("sway_periods", p.sway_periods);
  if (!(p.start_s >= 0.0) || !(p.move_s > 0.0) || !(p.sway_hz > 0.0) || p.sway_periods < 0) {
    throw wbi::runtime::ParameterError(
        parameters.where() +
        ": start_s must be >= 0, move_s and sway_frequency_hz > 0, sway_periods >= 0");
  }
}

void LabPosturePlanner::on_configure(const wbi::runtime::Parameters& parameters,
                                     const wbi::runtime::ComponentContext& context) {
  wbi::DdsInterfaceOptions options = wbi::controllers::read_interface_options(parameters, context);
  options.claim = wbi::DdsInterfaceOptions::Claim::none;  // it reads, it never commands
  options.blocking_read_timeout = milliseconds(parameters.get<double>("state_timeout_s", 0.005));
  const auto joints = parameters.require<std::vector<std::string>>("joints");
  const auto controller = parameters.require<std::string>("controller");
  const auto input = parameters.get<std::string>("input", "posture");
  const int n = static_cast<int>(joints.size());
  read_trajectory(parameters, n);
  const double init_timeout_s = parameters.get<double>("init_timeout_s", 30.0);

  writer_ = std::make_unique<wbi::controllers::ReferenceWriter>(
      *context.participant, options.robot, controller, input, context.instance);
  robot_ = wbi::make_dds_interface(options);
  robot_->add_joints(joints);
  robot_->init(milliseconds(init_timeout_s));
  state_ = wbi::RobotState(n);
  x_.setZero(n);
  v_.setZero(n);
  a_.setZero(n);
  start_ns_ = last_state_ns_ = last_sent_ns_ = -1;
  step_ns_ = 0;
  states_ = first_again_ = 0;
  std::printf(
      "lab_posture_planner: to the target in %.3g s from t = %.3g s, then %d sway period(s) at "
      "%.3g Hz, until t = %.3g s; points on %s\n",
      trajectory_.move_s, trajectory_.start_s, trajectory_.sway_periods, trajectory_.sway_hz,
      trajectory_.end_s(), writer_->topic().c_str());
  std::fflush(stdout);
}

bool LabPosturePlanner::wait_for_event(std::int64_t /*timeout_ns*/) {
  try {
    robot_->state().read_robot_state(state_, wbi::ReadMode::blocking);
    return true;
  } catch (const wbi::TimeoutError&) {
  } catch (const wbi::StaleDataError&) {
  }
  // No new state: while the robot waits at its first state, a cycle all the
  // same, to send the first point again (update()).
  return states_ == 1;
}

void LabPosturePlanner::update(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) {
  const std::int64_t stamp = state_.stamp.source_ns;
  if (stamp == last_state_ns_) {
    if (states_ == 1) {
      // A lockstep robot waits at its first state for its controller, whose
      // reader may join after the first point was sent (points are not kept
      // for late joiners): the controller would wait for it in vain.
      send(stamp);
      ++first_again_;
    }
    return;
  }
  if (stamp < last_state_ns_) {
    std::printf("lab_posture_planner: the robot's time went back to %.3f s: starting over\n",
                1e-9 * static_cast<double>(stamp));
    std::fflush(stdout);
    start_ns_ = last_state_ns_ = last_sent_ns_ = -1;
    step_ns_ = 0;
    states_ = 0;
  }
  if (last_state_ns_ >= 0) {
    const std::int64_t step = stamp - last_state_ns_;  // a late read skips states
    step_ns_ = step_ns_ > 0 ? std::min(step_ns_, step) : step;
  }
  last_state_ns_ = stamp;
  ++states_;
  if (start_ns_ < 0) {
    start_ns_ = stamp;
    trajectory_.from = state_.q;  // the posture it starts from: the robot's now
  }
  if (stamp > last_sent_ns_) {
    send(stamp);
  }
  // The points up to the next state's, now (a few at most after a late read).
  for (int ahead = 0; step_ns_ > 0 && ahead < 4 && last_sent_ns_ < stamp + step_ns_; ++ahead) {
    send(last_sent_ns_ + step_ns_);
  }
}

void LabPosturePlanner::send(std::int64_t stamp_ns) {
  trajectory_.at(1e-9 * static_cast<double>(stamp_ns - start_ns_), x_, v_, a_);
  writer_->write(stamp_ns, {x_.data(), static_cast<std::size_t>(x_.size())},
                 {v_.data(), static_cast<std::size_t>(v_.size())},
                 {a_.data(), static_cast<std::size_t>(a_.size())});
  last_sent_ns_ = stamp_ns;
}

void LabPosturePlanner::on_shutdown() {
  if (writer_) {
    std::printf(
        "lab_posture_planner: %llu points sent (%llu of them the first again, while the robot "
        "waited for its controller), the last for t = %.3f s\n",
        static_cast<unsigned long long>(writer_->written()),
        static_cast<unsigned long long>(first_again_),
        start_ns_ < 0 ? 0.0 : 1e-9 * static_cast<double>(last_sent_ns_ - start_ns_));
    std::fflush(stdout);
  }
  writer_.reset();
  if (robot_) {
    robot_->close();
  }
}

}  // namespace lab
