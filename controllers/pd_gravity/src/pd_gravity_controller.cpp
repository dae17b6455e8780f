#include "wbi/controllers/pd_gravity_controller.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace wbi::controllers {

namespace {
// Minimum jerk from 0 to 1 over τ ∈ [0, 1]: zero velocity and acceleration at both ends.
double minimum_jerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}

}  // namespace

std::vector<ParameterSpec> PdGravityController::parameters() const {
  return {
      {.name = "target", .unit = "rad", .help = "q_d, one per controlled joint", .size = kPerJoint},
      {.name = "bandwidth_hz",
       .unit = "Hz",
       .help = "gains from the joint inertia at the target: every mode critically damped",
       .default_value = {5.0},
       .min = 1e-3,
       .max = 200.0,
       .live = false},
      {.name = "kp",
       .unit = "N m/rad",
       .help = "diagonal stiffness instead of bandwidth_hz (with kd)",
       .size = kPerJoint,
       .min = 0.0,
       .live = false,
       .optional = true},
      {.name = "kd",
       .unit = "N m s/rad",
       .help = "diagonal damping instead of bandwidth_hz (with kp)",
       .size = kPerJoint,
       .min = 0.0,
       .live = false,
       .optional = true},
      {.name = "gain_scale",
       .help = "multiplies K_p and K_d",
       .default_value = {1.0},
       .min = 0.0,
       .max = 10.0},
      {.name = "transition_s",
       .unit = "s",
       .help = "time the reference takes to reach a new target (minimum jerk); 0: a step",
       .default_value = {0.0},
       .min = 0.0,
       .max = 600.0},
  };
}

std::vector<std::string> PdGravityController::signal_names() const {
  return {"max_joint_error", "reference_to_target"};
}

void PdGravityController::size_for(WholeBodyInterface& robot) {
  robot_ = &robot;
  const int n = robot.dofs();
  law_.emplace(robot);
  // Commanding some of the host's joints, it follows its own targets only.
  law_->set_own_joints(joints_);
  mass_matrix_.setZero(n + 6, n + 6);
  from_.setZero(n);
  goal_.setZero(n);
  reference_.setZero(n);
}

void PdGravityController::bind_joints(std::span<const int> joints) {
  joints_.assign(joints.begin(), joints.end());  // before configure (the contract)
}

void PdGravityController::gains_from_inertia(const Eigen::VectorXd& posture,
                                             const Transform& world_H_base, double bandwidth_hz) {
  const int n = robot_->dofs();
  robot_->mass_matrix(posture, world_H_base, mass_matrix_);
  law_->gains() = PdGravityGains::from_inertia(mass_matrix_.bottomRightCorner(n, n), bandwidth_hz);
}

void PdGravityController::configure(WholeBodyInterface& robot, const ParameterTable& parameters) {
  size_for(robot);
  index_ = {parameters.index("target"),     parameters.index("bandwidth_hz"),
            parameters.index("kp"),         parameters.index("kd"),
            parameters.index("gain_scale"), parameters.index("transition_s")};
  if (parameters.is_set(index_.kp) != parameters.is_set(index_.kd)) {
    throw Error(parameters.owner() + ": give both kp and kd, or neither (gains from bandwidth_hz)");
  }
  goal_ = Eigen::Map<const Eigen::VectorXd>(parameters.values(index_.target).data(), robot.dofs());
  if (parameters.is_set(index_.kp)) {
    const auto n = robot.dofs();
    auto& gains = law_->gains();
    gains.kp =
        Eigen::Map<const Eigen::VectorXd>(parameters.values(index_.kp).data(), n).asDiagonal();
    gains.kd =
        Eigen::Map<const Eigen::VectorXd>(parameters.values(index_.kd).data(), n).asDiagonal();
  } else {
    // Every mode critically damped at the bandwidth, from the inertia at the target.
    gains_from_inertia(goal_, Transform::Identity(), parameters.value(index_.bandwidth));
  }
  parameters_changed(parameters);
  reference_ = goal_;
}

void PdGravityController::parameters_changed(const ParameterTable& parameters) {
  law_->set_gain_scale(parameters.value(index_.scale));
  transition_s_ = parameters.value(index_.transition);
  const auto target = parameters.values(index_.target);
  if (!std::equal(target.begin(), target.end(), goal_.data())) {
    from_ = reference_;  // a new target: the reference moves on from where it is
    goal_ = Eigen::Map<const Eigen::VectorXd>(target.data(), robot_->dofs());
    transition_start_s_ = -1.0;
  }
}

void PdGravityController::activate(const RobotState& measured) {
  robot_->set_control_mode(ControlMode::torque);

  from_ = measured.q;
  reference_ = transition_s_ > 0.0 ? from_ : goal_;
  transition_start_s_ = -1.0;
}

// The paper's loop (PdGravity::update) about a reference that reaches the target.
bool PdGravityController::update(double time_s, double /*period_s*/) {
  if (transition_start_s_ < 0.0) {
    transition_start_s_ = time_s;
  }
  if (transition_s_ > 0.0) {
    const double s = minimum_jerk((time_s - transition_start_s_) / transition_s_);
    reference_ = from_ + s * (goal_ - from_);
  } else {
    reference_ = goal_;
  }
  law_->set_reference(reference_);
  law_->compute(ReadMode::latest);
  signals_[0] = law_->max_error();
  if (!joints_.empty()) {  // on its own joints (a host may give the others to another)
    signals_[0] = 0.0;
    for (const int j : joints_) {
      signals_[0] = std::max(signals_[0], std::abs(law_->state().q[j] - reference_[j]));
    }
  }
  signals_[1] = (reference_ - goal_).cwiseAbs().maxCoeff();
  return true;
}

void PdGravityController::progress(char* line, std::size_t size) const {
  std::snprintf(line, size, "max joint error %.4f rad", signals_[0]);
}

std::string PdGravityController::summary() const {
  char line[64];
  std::snprintf(line, sizeof line, "final max joint error: %.9g rad", signals_[0]);
  return line;
}

void register_pd_gravity(ControllerRegistry& registry) {
  registry.add<PdGravityController>("pd_gravity",
                                    "PD + gravity compensation towards a target posture");
}

}  // namespace wbi::controllers
