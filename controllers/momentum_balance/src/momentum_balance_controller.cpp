#include "wbi/controllers/momentum_balance_controller.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include <wbi/controllers/posture_parameter.hpp>

#include <wbi/vocabulary/joined_names.hpp>

namespace wbi::controllers {

namespace {

const MomentumBalanceParameters kDefaults{};

}  // namespace

std::vector<ParameterSpec> MomentumBalanceController::parameters() const {
  const auto& d = kDefaults;
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {.name = "left_sole",
       .help = "left contact frame",
       .text = true,
       .text_default = d.left_sole},
      {.name = "right_sole",
       .help = "right contact frame",
       .text = true,
       .text_default = d.right_sole},
      number_parameter("foot_x_min", "m", d.foot_x_min, -1.0, 0.0, false,
                       "support rectangle, sole frame"),
      number_parameter("foot_x_max", "m", d.foot_x_max, 0.0, 1.0, false,
                       "support rectangle, sole frame"),
      number_parameter("foot_y_min", "m", d.foot_y_min, -1.0, 0.0, false,
                       "support rectangle, sole frame"),
      number_parameter("foot_y_max", "m", d.foot_y_max, 0.0, 1.0, false,
                       "support rectangle, sole frame"),
      number_parameter("friction", "", d.friction, 1e-3, 10.0, false, "friction pyramid's mu"),
      number_parameter("torsional_friction", "m", d.torsional_friction, 0.0, 1.0, false,
                       "|tau_z| <= this x f_z"),
      number_parameter("min_normal_force", "N", d.min_normal_force, 0.0, inf, false, "per foot"),
      number_parameter("com_kp", "1/s^2", d.com_kp, 0.0, inf, true, "CoM stiffness"),
      number_parameter("com_kd", "1/s", d.com_kd, 0.0, inf, true, "CoM damping"),
      number_parameter("angular_momentum_kd", "1/s", d.angular_momentum_kd, 0.0, inf, true,
                       "angular momentum damping"),
      number_parameter("posture_bandwidth_hz", "Hz", d.posture_bandwidth_hz, 0.0, 100.0, false,
                       "null-space joint PD"),
      number_parameter("torque_weight", "", d.torque_weight, 0.0, inf, true,
                       "of |tau|^2 in the QP"),
      number_parameter("wrench_weight", "", d.wrench_weight, 1e-12, inf, true,
                       "|f|^2 regularisation"),
      number_parameter("foot_moment_weight", "", d.foot_moment_weight, 0.0, inf, true,
                       "extra weight on the feet moments"),
      {.name = "contact_forces",
       .help = "planned: the torques are those of the QP's feet wrenches; estimated: they are "
               "corrected so that the feet carry them, by the feet wrenches the state estimates "
               "from F/T sensors",
       .text = true,
       .text_default = "planned"},
      {.name = "left_wrench_links",
       .help = "with contact_forces: estimated, the left foot's links among the state's external "
               "wrenches, joined by + (default: left_sole)",
       .text = true},
      {.name = "right_wrench_links",
       .help = "likewise for the right foot (default: right_sole)",
       .text = true},
      number_parameter(
          "wrench_correction", "", d.wrench_correction, 0.0, 1.0, true,
          "with contact_forces: estimated, the share of the feet wrenches' error corrected"),
      number_parameter("wrench_correction_cutoff_hz", "Hz", d.wrench_correction_cutoff_hz, 1e-3,
                       1000.0, false, "low-pass of the feet wrenches' error"),
      posture_parameter(),
      number_parameter("settle_s", "s", 0.5, 0.0, inf, false,
                       "CoM error figures count from this long after activation"),
      number_parameter("exit_after_s", "s", 0.0, 0.0, inf, false,
                       "end the run after this long (0: never)"),
  };
}

std::vector<ReferenceSpec> MomentumBalanceController::references() const {
  return {{.name = "com",
           .unit = "m",
           .help = "CoM position, velocity, acceleration (world frame)",
           .size = 3,
           .max_age_s = 0.05,
           .rule = StaleRule::decay_to_state,
           .decay_s = 0.5}};
}

std::vector<std::string> MomentumBalanceController::signal_names() const {
  return {"com_x",     "com_y",     "com_z",    "com_ref_x", "com_ref_y",
          "com_ref_z", "com_error", "left_f_z", "right_f_z"};
}

void MomentumBalanceController::configure(WholeBodyInterface& robot,
                                          const ParameterTable& parameters) {
  robot_ = &robot;
  const auto value = [&](const char* name) { return parameters.value(parameters.index(name)); };
  // The configure-time fields here, the live ones by parameters_changed() below.
  MomentumBalanceParameters& p = tracking_;
  p = MomentumBalanceParameters{};
  p.left_sole = parameters.text(parameters.index("left_sole"));
  p.right_sole = parameters.text(parameters.index("right_sole"));
  p.foot_x_min = value("foot_x_min");
  p.foot_x_max = value("foot_x_max");
  p.foot_y_min = value("foot_y_min");
  p.foot_y_max = value("foot_y_max");
  p.friction = value("friction");
  p.torsional_friction = value("torsional_friction");
  p.min_normal_force = value("min_normal_force");
  p.posture_bandwidth_hz = value("posture_bandwidth_hz");
  const std::string& contact_forces = parameters.text(parameters.index("contact_forces"));
  if (contact_forces != "planned" && contact_forces != "estimated") {
    throw Error("momentum_balance: contact_forces is '" + contact_forces +
                "'; expected planned or estimated");
  }
  p.estimated_contact_forces = contact_forces == "estimated";
  p.wrench_correction_cutoff_hz = value("wrench_correction_cutoff_hz");
  p.left_wrench_links = split_joined_names(parameters.text(parameters.index("left_wrench_links")));
  p.right_wrench_links =
      split_joined_names(parameters.text(parameters.index("right_wrench_links")));
  const Eigen::VectorXd posture = read_posture(robot, parameters);
  settle_s_ = value("settle_s");
  exit_after_s_ = value("exit_after_s");
  balance_.reset();
  live_ = {parameters.index("com_kp"),
           parameters.index("com_kd"),
           parameters.index("angular_momentum_kd"),
           parameters.index("torque_weight"),
           parameters.index("wrench_weight"),
           parameters.index("foot_moment_weight"),
           parameters.index("wrench_correction")};
  parameters_changed(parameters);  // the live gains into tracking_
  balance_.emplace(robot, tracking_, posture);
}

void MomentumBalanceController::parameters_changed(const ParameterTable& parameters) {
  tracking_.com_kp = parameters.value(live_[0]);
  tracking_.com_kd = parameters.value(live_[1]);
  tracking_.angular_momentum_kd = parameters.value(live_[2]);
  tracking_.torque_weight = parameters.value(live_[3]);
  tracking_.wrench_weight = parameters.value(live_[4]);
  tracking_.foot_moment_weight = parameters.value(live_[5]);
  tracking_.wrench_correction = parameters.value(live_[6]);
  if (balance_) {
    balance_->set_tracking(tracking_);
  }
}

void MomentumBalanceController::activate(const RobotState& /*measured*/) {
  balance_->start();
  answered_.reset();
}

void MomentumBalanceController::state_source_changed() { new_estimator_ = true; }

bool MomentumBalanceController::update(double /*time_s*/, double /*period_s*/) {
  const Stamp stamp = balance_->read_state(ReadMode::latest);
  if (!answered_.take(stamp)) {
    return false;  // this estimate was answered already
  }
  if (!answered_.first() && new_estimator_) {
    // A new estimator: its world frame need not be the old one's (a legged
    // base starts at x = y = 0 wherever the robot stands). The reference
    // moves with the frame, so that the robot does not (it moved 5 cm to the
    // shifted reference before). The frames' offset is measured on the feet,
    // which stand still, not on the CoM, which moved during the outage (up
    // to 2 cm in 0.5 s at the sinusoid's peak speed; likely why a CI run once
    // ended an estimator restart 1 cm off the reference).
    const Eigen::Vector3d shift = balance_->feet_center_of_state() - balance_->feet_center();
    frame_shift_ += shift;
    ++new_estimators_;
    std::printf("new estimator: CoM reference moved with its frame by (%.4f, %.4f, %.4f) m\n",
                shift.x(), shift.y(), shift.z());
    std::fflush(stdout);
    new_estimator_ = false;
  }
  const double t = answered_.time_s();
  follow_reference(stamp.source_ns);
  balance_->compute();
  // The run's figures end at exit_after_s: the ticks answered while the
  // process shuts down are not counted (how many depends on timing).
  if (t >= settle_s_ && !finished_ && reference_came_) {
    const double error = (balance_->com() - balance_->com_reference()).norm();
    squared_error_ += error * error;
    max_error_ = std::max(max_error_, error);
    ++samples_;
    const auto net_miss = balance_->net_wrench(balance_->wrench_miss());
    squared_force_miss_ += net_miss.head<3>().squaredNorm();
    squared_moment_miss_ += net_miss.tail<3>().squaredNorm();
  }
  publish_signals();
  finished_ = exit_after_s_ > 0.0 && t >= exit_after_s_;
  return true;
}

void MomentumBalanceController::follow_reference(std::int64_t stamp_ns) {
  ReferenceInput& com = *com_input_;
  const ReferenceStatus status =
      com.at(stamp_ns, [&] { return Eigen::Vector3d(balance_->com_of_state() - frame_shift_); });
  // Before the first point the reference is the measured CoM itself: an
  // error against it would say nothing of tracking.
  reference_came_ = reference_came_ || status != ReferenceStatus::missing;
  balance_->set_com_reference(com.position() + frame_shift_, com.velocity(), com.acceleration());
}

void MomentumBalanceController::publish_signals() {
  const Eigen::Vector3d& c = balance_->com();
  const Eigen::Vector3d& r = balance_->com_reference();
  const auto& w = balance_->wrenches();
  signals_ = {c.x(), c.y(), c.z(), r.x(), r.y(), r.z(), (c - r).norm(), w[2], w[8]};
}

void MomentumBalanceController::progress(char* line, std::size_t size) const {
  const Eigen::Vector3d& c = balance_->com();
  const auto& w = balance_->wrenches();
  std::snprintf(line, size, "com (%.4f, %.4f, %.4f) m  error %.4f m  feet f_z %.1f / %.1f N", c.x(),
                c.y(), c.z(), (c - balance_->com_reference()).norm(), w[2], w[8]);
}

std::string MomentumBalanceController::figures_missing() const {
  if (samples_ > 0) {
    return {};
  }
  return reference_came_ ? "no tick counted after settle_s (the run ended first)"
                         : "no CoM reference point came on " + com_input_->owner() +
                               ": is its planner running?";
}

std::string MomentumBalanceController::summary() const {
  char text[256];
  if (samples_ == 0) {
    std::snprintf(
        text, sizeof text, "qp failures: %llu\nmax com error: none\ncom tracking rms: none (%s)",
        static_cast<unsigned long long>(balance_->qp_failures()), figures_missing().c_str());
    return text;
  }
  const auto samples = static_cast<double>(samples_);
  std::snprintf(text, sizeof text,
                "qp failures: %llu\nmax com error: %.6f m\ncom tracking rms: %.6f m",
                static_cast<unsigned long long>(balance_->qp_failures()), max_error_,
                std::sqrt(squared_error_ / samples));
  std::string summary = text;
  if (tracking_.estimated_contact_forces) {
    // The net wrench on the robot, estimated against planned, below the correction's
    // cutoff: what the momentum sees of the model's error.
    std::snprintf(text, sizeof text,
                  "\nfeet net wrench, estimated - planned, low-passed, rms: force %.3f N, moment "
                  "about the CoM %.3f N m",
                  std::sqrt(squared_force_miss_ / samples),
                  std::sqrt(squared_moment_miss_ / samples));
    summary += text;
  }
  return summary;
}

void register_momentum_balance(ControllerRegistry& registry) {
  registry.add<MomentumBalanceController>(
      "momentum_balance",
      "momentum-based balancing on two feet, following a CoM reference input (com)");
}

}  // namespace wbi::controllers
