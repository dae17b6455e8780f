#include "wbi/controllers/walking_controller.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include <wbi/controllers/posture_parameter.hpp>

namespace wbi::controllers::walking {

namespace {

const WalkingQpParameters kDefaults{};
const double kInfinity = std::numeric_limits<double>::infinity();

ParameterSpec text(const char* name, const std::string& value, const char* help) {
  return {.name = name, .help = help, .text = true, .text_default = value};
}

// The live gains and weights, in the order of WalkingController::live_.
struct LiveField {
  const char* name;
  const char* unit;
  double WalkingQpParameters::*field;
  const char* help;
};
constexpr LiveField kLive[] = {
    {"dcm_gain", "1/s", &WalkingQpParameters::dcm_gain, "DCM feedback k_xi"},
    {"com_height_kp", "1/s^2", &WalkingQpParameters::com_height_kp, "CoM height stiffness"},
    {"com_height_kd", "1/s", &WalkingQpParameters::com_height_kd, "CoM height damping"},
    {"angular_momentum_kd", "1/s", &WalkingQpParameters::angular_momentum_kd,
     "angular momentum damping"},
    {"swing_kp", "1/s^2", &WalkingQpParameters::swing_kp, "swing foot pose stiffness"},
    {"swing_kd", "1/s", &WalkingQpParameters::swing_kd, "swing foot pose damping"},
    {"torso_kp", "1/s^2", &WalkingQpParameters::torso_kp, "torso orientation stiffness"},
    {"torso_kd", "1/s", &WalkingQpParameters::torso_kd, "torso orientation damping"},
    {"momentum_weight", "", &WalkingQpParameters::momentum_weight, "of the momentum rate task"},
    {"angular_momentum_weight", "", &WalkingQpParameters::angular_momentum_weight,
     "of the angular momentum rate, x momentum_weight"},
    {"swing_weight", "", &WalkingQpParameters::swing_weight, "of the swing foot task"},
    {"torso_weight", "", &WalkingQpParameters::torso_weight, "of the torso task"},
    {"posture_weight", "", &WalkingQpParameters::posture_weight,
     "of the posture task, joints that move no sole"},
    {"leg_posture_weight", "", &WalkingQpParameters::leg_posture_weight,
     "of the posture task, joints that move a sole"},
    {"torque_weight", "", &WalkingQpParameters::torque_weight, "of |tau / m|^2"},
    {"step_adjustment_gain", "", &WalkingQpParameters::step_adjustment_gain,
     "a swinging foot lands off its plan by this x the DCM error beyond the dead band"},
    {"step_adjustment_dead_band", "m", &WalkingQpParameters::step_adjustment_dead_band,
     "DCM error not corrected by a step"},
    {"max_step_adjustment", "m", &WalkingQpParameters::max_step_adjustment,
     "the largest step adjustment"},
};

}  // namespace

std::vector<ParameterSpec> WalkingController::parameters() const {
  const auto& d = kDefaults;
  std::vector<ParameterSpec> specs = {
      text("left_sole", d.left_sole, "left contact frame (z up, x forward)"),
      text("right_sole", d.right_sole, "right contact frame"),
      text("torso", d.torso, "the link held upright, heading with the feet"),
      number_parameter("foot_x_min", "m", d.support.x_min, -1.0, 0.0, false,
                       "support rectangle, sole frame"),
      number_parameter("foot_x_max", "m", d.support.x_max, 0.0, 1.0, false,
                       "support rectangle, sole frame"),
      number_parameter("foot_y_min", "m", d.support.y_min, -1.0, 0.0, false,
                       "support rectangle, sole frame"),
      number_parameter("foot_y_max", "m", d.support.y_max, 0.0, 1.0, false,
                       "support rectangle, sole frame"),
      number_parameter("friction", "", d.support.friction, 1e-3, 10.0, false,
                       "friction pyramid's mu"),
      number_parameter("torsional_friction", "m", d.support.torsional_friction, 0.0, 1.0, false,
                       "|tau_z| <= this x f_z"),
      number_parameter("min_normal_force", "N", d.min_normal_force, 0.0, kInfinity, false,
                       "a foot in contact, at full weight"),
      number_parameter("max_normal_force", "", d.max_normal_force, 1e-3, kInfinity, false,
                       "a foot's normal force at most this x m g, at full weight"),
      number_parameter("posture_bandwidth_hz", "Hz", d.posture_bandwidth_hz, 0.0, 100.0, false,
                       "postural task"),
      posture_parameter(),
      number_parameter("exit_after_s", "s", 0.0, 0.0, kInfinity, false,
                       "end the run this long after activation (0: never)"),
      number_parameter("fall_height", "m", 0.2, 0.0, kInfinity, false,
                       "the base below this height above the lower sole is a fall"),
      number_parameter("speed_distance", "m", 1.0, 1e-3, kInfinity, false,
                       "the forward speed figure is timed over this much of the CoM's travel"),
  };
  for (const LiveField& live : kLive) {
    specs.push_back(
        number_parameter(live.name, live.unit, d.*live.field, 0.0, kInfinity, true, live.help));
  }
  return specs;
}

std::vector<ReferenceSpec> WalkingController::references() const {
  return {{.name = "walk",
           .unit = "m, rad",
           .help = "DCM, CoM, soles (x, y, z, yaw), contact weights (walking_plan.hpp)",
           .size = kWalkReferenceSize,
           .max_age_s = 0.05,
           .rule = StaleRule::hold_last}};
}

std::vector<std::string> WalkingController::signal_names() const {
  return {"com_x",     "com_y",    "com_z",     "dcm_x",        "dcm_y",         "dcm_ref_x",
          "dcm_ref_y", "left_f_z", "right_f_z", "left_contact", "right_contact", "steps"};
}

void WalkingController::configure(WholeBodyInterface& robot, const ParameterTable& parameters) {
  const auto value = [&](const char* name) { return parameters.value(parameters.index(name)); };
  WalkingQpParameters& p = configured_;
  p = WalkingQpParameters{};
  p.left_sole = parameters.text(parameters.index("left_sole"));
  p.right_sole = parameters.text(parameters.index("right_sole"));
  p.torso = parameters.text(parameters.index("torso"));
  p.support = {.x_min = value("foot_x_min"),
               .x_max = value("foot_x_max"),
               .y_min = value("foot_y_min"),
               .y_max = value("foot_y_max"),
               .friction = value("friction"),
               .torsional_friction = value("torsional_friction")};
  p.min_normal_force = value("min_normal_force");
  p.max_normal_force = value("max_normal_force");
  p.posture_bandwidth_hz = value("posture_bandwidth_hz");
  exit_after_s_ = value("exit_after_s");
  fall_height_ = value("fall_height");
  speed_distance_ = value("speed_distance");
  live_.clear();
  for (const LiveField& live : kLive) {
    live_.push_back(parameters.index(live.name));
  }
  parameters_changed(parameters);
  const Eigen::VectorXd posture = read_posture(robot, parameters);
  qp_.reset();
  qp_.emplace(robot, configured_, posture);
}

void WalkingController::parameters_changed(const ParameterTable& parameters) {
  for (std::size_t k = 0; k < live_.size(); ++k) {
    configured_.*kLive[k].field = parameters.value(live_[k]);
  }
  if (qp_) {
    qp_->set_gains(configured_);
  }
}

void WalkingController::activate(const RobotState& measured) {
  qp_->start(measured);
  figures_.reset(fall_height_, speed_distance_);
  finished_ = false;
  answered_.reset();
}

bool WalkingController::update(double /*time_s*/, double /*period_s*/) {
  const Stamp stamp = qp_->read_state(ReadMode::latest);
  if (!answered_.take(stamp)) {
    return false;  // this estimate was answered already
  }
  const double t = answered_.time_s();
  read_targets(stamp.source_ns);
  qp_->compute(targets_);
  if (!finished_) {
    figures_.add(t, targets_, *qp_);
  }
  publish_signals();
  finished_ = finished_ || figures_.fell() || (exit_after_s_ > 0.0 && t >= exit_after_s_);
  return true;
}

// The plan's point for this state; before the first (and by hold_last after
// the last), standing still on the measured feet.
void WalkingController::read_targets(std::int64_t stamp_ns) {
  walk_->at(stamp_ns, [&] {
    qp_->standing_targets(standing_);
    Eigen::Matrix<double, kWalkReferenceSize, 1> at_rest;
    at_rest << standing_.dcm, standing_.com, standing_.feet[0].position, standing_.feet[0].yaw,
        standing_.feet[1].position, standing_.feet[1].yaw, 1.0, 1.0;
    return at_rest;
  });
  reference_.position = walk_->position();
  reference_.velocity = walk_->velocity();
  reference_.acceleration = walk_->acceleration();
  targets_.read(reference_);
}

void WalkingController::publish_signals() {
  const Eigen::Vector3d& c = qp_->com();
  const Eigen::Vector3d& xi = qp_->dcm();
  const auto& w = qp_->wrenches();
  signals_ = {c.x(),
              c.y(),
              c.z(),
              xi.x(),
              xi.y(),
              targets_.dcm.x(),
              targets_.dcm.y(),
              w[2],
              w[8],
              targets_.contact_weight[0],
              targets_.contact_weight[1],
              static_cast<double>(figures_.steps())};
}

void WalkingController::progress(char* line, std::size_t size) const {
  const Eigen::Vector3d& c = qp_->com();
  std::snprintf(line, size,
                "com (%.3f, %.3f, %.3f) m  steps %d  dcm error %.4f m  feet f_z %.0f / %.0f N",
                c.x(), c.y(), c.z(), figures_.steps(), (qp_->dcm() - targets_.dcm).head<2>().norm(),
                qp_->wrenches()[2], qp_->wrenches()[8]);
}

std::string WalkingController::summary() const {
  char text[64];
  std::snprintf(text, sizeof text, "qp failures: %llu\n",
                static_cast<unsigned long long>(qp_->qp_failures()));
  return text + figures_.text();
}

std::string WalkingController::figures_missing() const {
  if (figures_.fell()) {
    char text[96];
    std::snprintf(text, sizeof text, "the robot fell at t = %.3f s", figures_.fall_time());
    return text;
  }
  if (walk_->received() == 0) {
    return "no walking reference point came on " + walk_->owner() + ": is its planner running?";
  }
  return {};
}

void register_walking_controller(ControllerRegistry& registry) {
  registry.add<WalkingController>(
      "walking", "whole-body walking QP following a walking plan (input walk: walking_planner)");
}

}  // namespace wbi::controllers::walking
