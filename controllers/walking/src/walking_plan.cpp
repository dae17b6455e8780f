// WalkingPlan (walking_plan.hpp): footsteps, the DCM through them by the
// backward recursion of Englsberger et al. (T-RO 2015, section IV), the CoM
// in closed form, swing feet and contact weights. Planning builds in the
// scratch vectors and swaps, so a refused command leaves the plan as it was.
#include "wbi/controllers/walking_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <numbers>
#include <utility>

#include <wbi/types.hpp>

namespace wbi::controllers::walking {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMaxGoalDistance = 100.0;       // [m]
constexpr double kMaxGoalTurn = 4.0 * kPi;       // [rad]
constexpr std::size_t kMaxReservedSteps = 4096;  // more: that walk_to allocates
// Allowed beyond a limit [m, rad]: rounding, and feet measured a fraction of a
// millimetre off each other (2 m in 0.2 m steps from feet 0.03 mm apart was refused).
constexpr double kSlack = 1e-3;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

int index(Foot foot) { return static_cast<int>(foot); }
Foot other(Foot foot) { return foot == Foot::left ? Foot::right : Foot::left; }
const char* name(Foot foot) { return foot == Foot::left ? "left" : "right"; }

double wrap(double angle) { return std::remainder(angle, 2.0 * kPi); }  // to [−π, π]

Eigen::Vector2d rotated(double yaw, const Eigen::Vector2d& v) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

// One line of text (refusals only: they may allocate).
__attribute__((format(printf, 1, 2))) std::string line(const char* format, ...) {
  char text[320];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  return text;
}

// s(u) = 10u³ − 15u⁴ + 6u⁵ from 0 to 1: zero velocity and acceleration at both ends.
struct Blend {
  double s, ds, dds;  // value, d/du, d²/du²
};
Blend quintic(double u) {
  u = std::clamp(u, 0.0, 1.0);
  const double w = u * (1.0 - u);
  return {u * u * u * (10.0 + u * (-15.0 + 6.0 * u)), 30.0 * w * w, 60.0 * w * (1.0 - 2.0 * u)};
}
// b(u) = 64 u³(1−u)³: 0 at both ends with zero velocity and acceleration, 1 at u = ½.
Blend bump(double u) {
  u = std::clamp(u, 0.0, 1.0);
  const double w = u * (1.0 - u), dw = 1.0 - 2.0 * u;
  return {64.0 * w * w * w, 192.0 * w * w * dw, 384.0 * w * (dw * dw - w)};
}

// The cubic from (x0, v0) at τ = 0 to (x1, v1) at τ = T: coefficients of τ⁰…τ³.
std::array<Eigen::Vector3d, 4> hermite(const Eigen::Vector3d& x0, const Eigen::Vector3d& v0,
                                       const Eigen::Vector3d& x1, const Eigen::Vector3d& v1,
                                       double T) {
  const Eigen::Vector3d dx = x1 - x0;
  return {x0, v0, (3.0 * dx - (2.0 * v0 + v1) * T) / (T * T),
          (-2.0 * dx + (v0 + v1) * T) / (T * T * T)};
}

}  // namespace

WalkingPlan::WalkingPlan(WalkingParameters parameters) : p_(std::move(parameters)) {
  if (const std::string why = check_parameters(); !why.empty()) {
    throw Error(why);
  }
  // The longest walk_to: 100 m in the shortest step, 4π in the smallest turns.
  double shortest = std::min(p_.max_step_forward, p_.max_step_backward);
  const double lateral = std::min(p_.max_step_lateral, p_.step_width - p_.min_step_width);
  if (lateral > 0.0) {
    shortest = std::min(shortest, lateral);
  }
  const double most =
      std::ceil(kMaxGoalDistance / shortest) + std::ceil(kMaxGoalTurn / p_.max_step_turn) + 3.0;
  const auto steps = static_cast<std::size_t>(std::min(most, double(kMaxReservedSteps)));
  steps_.reserve(steps);
  scratch_steps_.reserve(steps);
  phases_.reserve(2 * steps + 2);
  scratch_phases_.reserve(2 * steps + 2);
  const double half = 0.5 * p_.step_width;
  stand(0.0, {Eigen::Vector3d(0.0, half, 0.0), 0.0}, {Eigen::Vector3d(0.0, -half, 0.0), 0.0},
        Eigen::Vector3d(0.0, 0.0, p_.com_height));
}

std::string WalkingPlan::check_parameters() const {
  const std::pair<const char*, double> positive[] = {
      {"single_support_s", p_.single_support_s},
      {"double_support_s", p_.double_support_s},
      {"final_double_support_s", p_.final_double_support_s},
      {"step_height", p_.step_height},
      {"com_height", p_.com_height},
      {"gravity", p_.gravity},
      {"step_width", p_.step_width},
      {"max_step_forward", p_.max_step_forward},
      {"max_step_backward", p_.max_step_backward},
      {"max_step_lateral", p_.max_step_lateral},
      {"max_step_turn", p_.max_step_turn},
      {"min_step_width", p_.min_step_width}};
  for (const auto& [parameter, value] : positive) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      return line("walking: %s = %g must be positive and finite", parameter, value);
    }
  }
  if (p_.min_step_width > p_.step_width) {
    return line("walking: min_step_width = %g is more than step_width = %g", p_.min_step_width,
                p_.step_width);
  }
  if (!p_.vrp_offset.allFinite()) {
    return "walking: vrp_offset has a NaN or infinite value";
  }
  return {};
}

double WalkingPlan::omega() const { return std::sqrt(p_.gravity / p_.com_height); }

Eigen::Vector3d WalkingPlan::vrp(const FootPose& sole) const {
  Eigen::Vector3d r = sole.position;
  r.head<2>() += rotated(sole.yaw, p_.vrp_offset.head<2>());
  r.z() += p_.vrp_offset.z() + p_.com_height;
  return r;
}

void WalkingPlan::stand(double t, const FootPose& left, const FootPose& right,
                        const Eigen::Vector3d& com) {
  steps_.clear();
  phases_.clear();
  Phase& rest = phases_.emplace_back();
  rest.kind = PhaseKind::rest;
  rest.begin = t;
  rest.duration = kInfinity;
  rest.dcm[0] = com;
  rest.com_begin = com;
  rest.feet_begin = {left, right};
}

bool WalkingPlan::walking(double t) const { return phases_.size() > 1 && t < end_time(); }

double WalkingPlan::end_time() const { return phases_.back().begin; }

const WalkingPlan::Phase& WalkingPlan::phase_at(double t) const {
  const auto after = std::upper_bound(phases_.begin(), phases_.end(), t,
                                      [](double time, const Phase& p) { return time < p.begin; });
  return after == phases_.begin() ? phases_.front() : *(after - 1);
}

std::string WalkingPlan::walk_to(double t, double dx, double dy, double dyaw) {
  const std::pair<const char*, double> values[] = {{"dx", dx}, {"dy", dy}, {"dyaw", dyaw}};
  for (const auto& [value_name, value] : values) {
    if (!std::isfinite(value)) {
      return line("walk_to: %s = %g is not a finite number", value_name, value);
    }
  }
  if (walking(t)) {
    return line(
        "walk_to: the robot is walking until t = %.3f s (now %.3f s): a command waits "
        "for the end of the walk",
        end_time(), t);
  }
  const double distance = std::hypot(dx, dy);
  if (distance > kMaxGoalDistance) {
    return line("walk_to: the goal (%g, %g) m is %.1f m away, more than %g m", dx, dy, distance,
                kMaxGoalDistance);
  }
  if (std::abs(dyaw) > kMaxGoalTurn) {
    return line("walk_to: dyaw = %g rad turns more than 4π", dyaw);
  }

  // How many straight steps: equal ones, the longest the limits allow along (dx, dy).
  const Eigen::Vector2d d(dx, dy);
  int straight = 0;
  if (distance > kSlack) {
    const Eigen::Vector2d u = d / distance;
    double longest = kInfinity;
    if (u.x() > 0.0) longest = p_.max_step_forward / u.x();
    if (u.x() < 0.0) longest = p_.max_step_backward / -u.x();
    if (u.y() != 0.0) {
      // Toward the stance foot a step may close the gap only down to min_step_width.
      const double lateral = std::min(p_.max_step_lateral, p_.step_width - p_.min_step_width);
      if (lateral <= 0.0) {
        return line(
            "walk_to: dy = %g needs sideways steps, and step_width = %g leaves none "
            "above min_step_width = %g",
            dy, p_.step_width, p_.min_step_width);
      }
      longest = std::min(longest, lateral / std::abs(u.y()));
    }
    straight = static_cast<int>(std::ceil(distance / longest - kSlack));
  }
  const int turning = std::abs(dyaw) > kSlack
                          ? static_cast<int>(std::ceil(std::abs(dyaw) / p_.max_step_turn - kSlack))
                          : 0;
  if (straight == 0 && turning == 0) {
    return {};  // there already: nothing to walk
  }

  // The middle of the feet and their mean heading now.
  const std::array<FootPose, 2>& feet = phase_at(t).feet_begin;
  const FootPose& left = feet[0];
  const FootPose& right = feet[1];
  const double heading = right.yaw + 0.5 * wrap(left.yaw - right.yaw);
  const Eigen::Vector3d middle = 0.5 * (left.position + right.position);
  scratch_steps_.clear();
  // A footstep: `along` from the middle (in the heading's frame), turned by `turn`.
  const auto place = [&](Foot foot, const Eigen::Vector2d& along, double turn) {
    const double side = foot == Foot::left ? 0.5 : -0.5;
    Footstep& step = scratch_steps_.emplace_back();
    step.foot = foot;
    step.pose.position = middle;
    step.pose.position.head<2>() +=
        rotated(heading, along) + rotated(heading + turn, {0.0, side * p_.step_width});
    step.pose.yaw = heading + turn;
  };

  // A turn opens with the foot on its side (no toes turned in against the
  // other foot); sideways steps open with the foot on the side of travel.
  const Foot turn_foot = dyaw >= 0.0 ? Foot::left : Foot::right;
  Foot next = Foot::left;
  if (straight > 0 && std::abs(dy) > kSlack) {
    next = dy > 0.0 ? Foot::left : Foot::right;
  } else if (turning > 0) {
    next = straight % 2 == 0 ? turn_foot : other(turn_foot);
  }
  for (int k = 1; k <= straight; ++k, next = other(next)) {
    place(next, (double(k) / straight) * d, 0.0);
  }
  if (turning > 0 && next != turn_foot) {
    place(next, d, 0.0);  // side by side first
    next = other(next);
  }
  for (int k = 1; k <= turning; ++k, next = other(next)) {
    place(next, d, dyaw * k / turning);
  }
  place(next, d, dyaw);  // the feet side by side
  const std::string why = plan(t);
  return why.empty() ? why : "walk_to: " + why;
}

std::string WalkingPlan::walk(double t, const std::vector<Footstep>& footsteps) {
  if (walking(t)) {
    return line(
        "walk: the robot is walking until t = %.3f s (now %.3f s): a command waits for "
        "the end of the walk",
        end_time(), t);
  }
  if (footsteps.empty()) {
    return {};
  }
  scratch_steps_ = footsteps;
  return plan(t);
}

// Each footstep against the stance foot it starts from (the other foot, where
// it stands then); its yaw is made the nearest to its foot's before (no turn
// by 2π).
std::string WalkingPlan::check_and_unwrap(std::array<FootPose, 2> feet) {
  for (std::size_t k = 0; k < scratch_steps_.size(); ++k) {
    Footstep& step = scratch_steps_[k];
    const int number = static_cast<int>(k) + 1;
    if (!step.pose.position.allFinite() || !std::isfinite(step.pose.yaw)) {
      return line("footstep %d has a NaN or infinite value", number);
    }
    if (k > 0 && step.foot == scratch_steps_[k - 1].foot) {
      return line("footstep %d moves the %s foot again: the feet alternate", number,
                  name(step.foot));
    }
    const FootPose& stance = feet[index(other(step.foot))];
    const Eigen::Vector2d offset =
        rotated(-stance.yaw, (step.pose.position - stance.position).head<2>());
    const double beside = step.foot == Foot::left ? offset.y() : -offset.y();
    const double turn = wrap(step.pose.yaw - stance.yaw);
    const char* foot = name(step.foot);
    const char* from = name(other(step.foot));
    if (offset.x() > p_.max_step_forward + kSlack) {
      return line("footstep %d (%s) is %.4g m ahead of the %s foot, beyond max_step_forward = %g m",
                  number, foot, offset.x(), from, p_.max_step_forward);
    }
    if (-offset.x() > p_.max_step_backward + kSlack) {
      return line("footstep %d (%s) is %.4g m behind the %s foot, beyond max_step_backward = %g m",
                  number, foot, -offset.x(), from, p_.max_step_backward);
    }
    if (std::abs(beside - p_.step_width) > p_.max_step_lateral + kSlack) {
      return line(
          "footstep %d (%s) is %.4g m beside the %s foot, beyond step_width = %g m ± "
          "max_step_lateral = %g m",
          number, foot, beside, from, p_.step_width, p_.max_step_lateral);
    }
    if (beside < p_.min_step_width - kSlack) {
      return line("footstep %d (%s) is %.4g m beside the %s foot, below min_step_width = %g m",
                  number, foot, beside, from, p_.min_step_width);
    }
    if (std::abs(turn) > p_.max_step_turn + kSlack) {
      return line(
          "footstep %d (%s) is turned %.4g rad from the %s foot, beyond max_step_turn = "
          "%g rad",
          number, foot, turn, from, p_.max_step_turn);
    }
    FootPose& moving = feet[index(step.foot)];
    step.pose.yaw = moving.yaw + wrap(step.pose.yaw - moving.yaw);
    moving = step.pose;
  }
  return {};
}

std::string WalkingPlan::plan(double t) {
  if (phases_.size() > 1) {
    t = std::max(t, end_time());  // a walk starts from rest
  }
  const Phase& now = phase_at(t);
  const std::array<FootPose, 2> feet = now.feet_begin;
  if (std::string why = check_and_unwrap(feet); !why.empty()) {
    return why;
  }
  Eigen::Vector3d dcm, com, v, a;
  dcm_at(now, t - now.begin, dcm, v, a);
  com_at(now, std::max(0.0, t - now.begin), com, v, a);
  fill_timing(t, feet);
  fill_dcm(dcm);
  fill_com(com);
  std::swap(steps_, scratch_steps_);
  std::swap(phases_, scratch_phases_);
  return {};
}

// Phases: double support 0, then single support i at 1 + 2i and double
// support i + 1 at 2 + 2i, then the rest. The feet where each begins, the
// contact weights at its ends.
void WalkingPlan::fill_timing(double t, const std::array<FootPose, 2>& feet) {
  const std::size_t n = scratch_steps_.size();
  std::vector<Phase>& phases = scratch_phases_;
  phases.assign(2 * n + 2, Phase{});
  std::array<FootPose, 2> now = feet;
  double begin = t;
  for (std::size_t j = 0; j < phases.size(); ++j) {
    Phase& phase = phases[j];
    const bool last = j + 1 == phases.size();
    phase.kind = last         ? PhaseKind::rest
                 : j % 2 == 1 ? PhaseKind::single_support
                              : PhaseKind::double_support;
    phase.begin = begin;
    phase.duration = last                                      ? kInfinity
                     : phase.kind == PhaseKind::single_support ? p_.single_support_s
                     : (j == 0 || j == 2 * n)                  ? p_.final_double_support_s
                                                               : p_.double_support_s;
    begin += phase.duration;
    phase.feet_begin = now;
    if (phase.kind == PhaseKind::single_support) {
      phase.step = static_cast<int>(j / 2);
      const Footstep& step = scratch_steps_[phase.step];
      now[index(step.foot)] = step.pose;
      phase.weight_begin[index(step.foot)] = phase.weight_end[index(step.foot)] = 0.0;
    }
  }
  // A double support ramps from the weights of the phase before to those after.
  for (std::size_t j = 0; j + 1 < phases.size(); j += 2) {
    phases[j].weight_begin = j == 0 ? std::array{1.0, 1.0} : phases[j - 1].weight_end;
    phases[j].weight_end = phases[j + 1].weight_begin;
  }
}

// Englsberger 2015, eq. (13)–(16) with a virtual VRP switch in the middle of
// each double support: from the rest point backwards, ξ at the end of a
// single support is r + e^{−ωT_ds/2}(ξ_switch − r) and at its start
// r + e^{−ωT_ss}(ξ_end − r). Each double support is then the cubic Hermite
// joining the single supports' (ξ, ξ̇) at its ends.
void WalkingPlan::fill_dcm(const Eigen::Vector3d& dcm_now) {
  std::vector<Phase>& phases = scratch_phases_;
  const std::size_t n = scratch_steps_.size();
  const double w = omega();
  const double half_double = std::exp(-w * 0.5 * p_.double_support_s);
  const double single = std::exp(-w * p_.single_support_s);
  const auto& final_feet = phases.back().feet_begin;
  const Eigen::Vector3d rest = 0.5 * (vrp(final_feet[0]) + vrp(final_feet[1]));
  phases.back().dcm[0] = rest;
  Eigen::Vector3d at_switch = rest;
  for (std::size_t i = n; i-- > 0;) {
    Phase& phase = phases[1 + 2 * i];
    const Eigen::Vector3d r = vrp(phase.feet_begin[index(other(scratch_steps_[i].foot))]);
    const Eigen::Vector3d at_end = r + half_double * (at_switch - r);
    phase.dcm[0] = r;
    phase.dcm[1] = single * (at_end - r);  // ξ(τ) = r + e^{ωτ} dcm[1]
    at_switch = r + half_double * phase.dcm[1];
  }
  const double grown = std::exp(w * p_.single_support_s);
  for (std::size_t j = 0; j + 1 < phases.size(); j += 2) {
    Eigen::Vector3d x0 = dcm_now, v0 = Eigen::Vector3d::Zero();
    Eigen::Vector3d x1 = rest, v1 = Eigen::Vector3d::Zero();
    if (j > 0) {
      const Phase& before = phases[j - 1];
      x0 = before.dcm[0] + grown * before.dcm[1];
      v0 = w * grown * before.dcm[1];
    }
    if (j + 2 < phases.size()) {
      const Phase& after = phases[j + 1];
      x1 = after.dcm[0] + after.dcm[1];
      v1 = w * after.dcm[1];
    }
    phases[j].dcm = hermite(x0, v0, x1, v1, phases[j].duration);
  }
}

// ẋ = ω (ξ − x) integrated phase by phase in closed form (com_at).
void WalkingPlan::fill_com(const Eigen::Vector3d& com_now) {
  std::vector<Phase>& phases = scratch_phases_;
  phases.front().com_begin = com_now;
  Eigen::Vector3d x, v, a;
  for (std::size_t j = 0; j + 1 < phases.size(); ++j) {
    com_at(phases[j], phases[j].duration, x, v, a);
    phases[j + 1].com_begin = x;
  }
}

void WalkingPlan::dcm_at(const Phase& phase, double tau, Eigen::Vector3d& x, Eigen::Vector3d& v,
                         Eigen::Vector3d& a) const {
  const auto& c = phase.dcm;
  switch (phase.kind) {
    case PhaseKind::double_support:
      x = c[0] + tau * (c[1] + tau * (c[2] + tau * c[3]));
      v = c[1] + tau * (2.0 * c[2] + 3.0 * tau * c[3]);
      a = 2.0 * c[2] + 6.0 * tau * c[3];
      return;
    case PhaseKind::single_support: {
      const double w = omega(), grown = std::exp(w * tau);
      x = c[0] + grown * c[1];
      v = w * grown * c[1];
      a = w * w * grown * c[1];
      return;
    }
    case PhaseKind::rest:
      x = c[0];
      v.setZero();
      a.setZero();
      return;
  }
}

// The CoM from com_begin under ẋ = ω (ξ − x), ξ this phase's DCM:
//   rest            x = ξ + (x₀ − ξ) e^{−ωτ}
//   single support  x = r + ½c e^{ωτ} + (x₀ − r − ½c) e^{−ωτ}       (ξ = r + c e^{ωτ})
//   double support  x = P(τ) + (x₀ − P(0)) e^{−ωτ}, P = p − p′/ω + p″/ω² − p‴/ω³ (ξ = p, a cubic)
// then ẋ = ω (ξ − x), ẍ = ω (ξ̇ − ẋ).
void WalkingPlan::com_at(const Phase& phase, double tau, Eigen::Vector3d& x, Eigen::Vector3d& v,
                         Eigen::Vector3d& a) const {
  const double w = omega(), decay = std::exp(-w * tau);
  const auto& c = phase.dcm;
  const Eigen::Vector3d& x0 = phase.com_begin;
  Eigen::Vector3d dcm, dcm_v, dcm_a;
  dcm_at(phase, tau, dcm, dcm_v, dcm_a);
  switch (phase.kind) {
    case PhaseKind::rest:
      x = dcm + (x0 - dcm) * decay;
      break;
    case PhaseKind::single_support:
      x = c[0] + 0.5 * c[1] / decay + (x0 - c[0] - 0.5 * c[1]) * decay;
      break;
    case PhaseKind::double_support: {
      const Eigen::Vector3d jerk = 6.0 * c[3];
      const Eigen::Vector3d particular = dcm - dcm_v / w + dcm_a / (w * w) - jerk / (w * w * w);
      const Eigen::Vector3d particular_0 =
          c[0] - c[1] / w + 2.0 * c[2] / (w * w) - jerk / (w * w * w);
      x = particular + (x0 - particular_0) * decay;
      break;
    }
  }
  v = w * (dcm - x);
  a = w * (dcm_v - v);
}

void WalkingPlan::sample(double t, WalkingReference& out) const {
  const Phase& phase = phase_at(t);
  const double tau = std::clamp(t - phase.begin, 0.0, phase.duration);
  Eigen::Vector3d x, v, a;
  dcm_at(phase, tau, x, v, a);
  out.position.segment<3>(0) = x;
  out.velocity.segment<3>(0) = v;
  out.acceleration.segment<3>(0) = a;
  com_at(phase, tau, x, v, a);
  out.position.segment<3>(3) = x;
  out.velocity.segment<3>(3) = v;
  out.acceleration.segment<3>(3) = a;

  const bool swinging = phase.kind == PhaseKind::single_support;
  const double u = phase.kind == PhaseKind::rest ? 1.0 : tau / phase.duration;
  for (int f = 0; f < 2; ++f) {
    const int at = 6 + 4 * f;
    const FootPose& from = phase.feet_begin[f];
    out.position.segment<3>(at) = from.position;
    out.position[at + 3] = from.yaw;
    out.velocity.segment<4>(at).setZero();
    out.acceleration.segment<4>(at).setZero();
    if (!swinging || index(steps_[phase.step].foot) != f) {
      continue;
    }
    // x, y, yaw by the quintic; z the same plus the bump up to step_height.
    const FootPose& to = steps_[phase.step].pose;
    const double T = phase.duration;
    const Blend s = quintic(u), h = bump(u);
    Eigen::Vector4d delta;
    delta << to.position - from.position, to.yaw - from.yaw;
    out.position.segment<4>(at) += s.s * delta;
    out.velocity.segment<4>(at) = (s.ds / T) * delta;
    out.acceleration.segment<4>(at) = (s.dds / (T * T)) * delta;
    out.position[at + 2] += p_.step_height * h.s;
    out.velocity[at + 2] += p_.step_height * h.ds / T;
    out.acceleration[at + 2] += p_.step_height * h.dds / (T * T);
  }

  const double ramp = phase.kind == PhaseKind::double_support ? quintic(u).s : 0.0;
  for (int f = 0; f < 2; ++f) {
    out.position[14 + f] = std::clamp(
        phase.weight_begin[f] + (phase.weight_end[f] - phase.weight_begin[f]) * ramp, 0.0, 1.0);
  }
  out.velocity.tail<2>().setZero();
  out.acceleration.tail<2>().setZero();
}

}  // namespace wbi::controllers::walking
