// SimBackend: the plant. Models and formulas: robot_side/sim/README.md.
#include "wbi/sim/sim_backend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <wbi/sim_models/command_hold.hpp>
#include <wbi/sim_models/sensor_actuator_models.hpp>
#include <wbi/sim_models/sensor_noise.hpp>
#include <wbi/sim_models/sim_plan.hpp>

#include "contact_points.hpp"
#include "force_torque_model.hpp"
#include "wbi/model/aba.hpp"
#include "wbi/model/com.hpp"
#include "wbi/model/crba.hpp"
#include "wbi/model/kinematics.hpp"
#include "wbi/model/urdf.hpp"

namespace wbi::sim {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using sim_models::SimPlan;

namespace {

// Force f at world point p as a world-origin wrench (f, p × f).
Vector6d wrench_at_origin(const Vector3d& f, const Vector3d& p) {
  Vector6d w;
  w.head<3>() = f;
  w.tail<3>() = p.cross(f);
  return w;
}

}  // namespace

struct SimBackend::Impl {
  model::Model model;
  SimPlan plan;                      // what the config asks, engine-neutral (sim_plan.hpp)
  std::optional<model::Data> data;   // dynamics (substeps)
  std::optional<model::Data> sense;  // kinematics for read() and helpers
  int n = 0;                         // joints

  // ---- per joint (size n) ----
  Eigen::VectorXd lower, upper, m_diag, k_limit, d_limit;
  sim_models::CommandHold commands;
  Eigen::VectorXd tau;  // [nv] joint-space generalized force of the substep

  // ---- contacts ----
  std::vector<model::ExternalWrench> wrenches;  // [n_links + n_pushes], used prefix n_wrenches
  std::size_t n_wrenches = 0;

  // ---- F/T sensors: the Newton–Euler of the part beyond each joint ----
  std::vector<ForceTorqueModel> fts;

  struct Push {
    std::int64_t start = 0, end = 0;  // substep indices: active for start ≤ k < end
    bool active = false;
  };
  std::vector<Push> pushes;  // [plan.pushes]

  sim_models::SensorNoise noise;
  std::int64_t substep_count = 0;  // substeps done since configure()

  explicit Impl(const RobotConfig& config) : noise(config) {}
};

SimBackend::SimBackend(RobotConfig config) : config_(std::move(config)) {}
SimBackend::~SimBackend() = default;

const model::Model& SimBackend::model() const {
  if (!impl_) {
    throw std::logic_error("SimBackend::model(): configure() first");
  }
  return impl_->model;
}

Duration SimBackend::step_period() const {
  return Duration(static_cast<std::int64_t>(config_.wbi.step * 1e9));
}

Time SimBackend::stamp() const {
  return Time(static_cast<std::int64_t>(std::llround(time_ * 1e9)));
}

actuation::BackendDescription SimBackend::on_configure() {
  const RobotConfig& c = config_;
  const WbiOptions& o = c.wbi;
  const std::string where = "robot config";
  if (c.urdf.empty()) {
    throw std::invalid_argument(where + ": 'urdf' is required");
  }
  if (!(o.step > 0.0) || o.substeps < 1) {
    throw std::invalid_argument(where + ": 'wbi.step' must be > 0 and 'wbi.substeps' >= 1");
  }
  robot_config::complete_from_urdf(config_);  // every joint's dynamics, URDF boxes if no contacts
  auto impl = std::make_unique<Impl>(c);
  Impl& s = *impl;
  model::LoadOptions options;
  options.fixed_base = c.fixed_base;
  options.armature = robot_config::armature_by_joint(c);
  try {
    s.model = model::load_urdf_file(c.urdf, options);
  } catch (const std::invalid_argument& error) {  // a joints: entry; name the key
    throw std::invalid_argument(where + ": joints: " + error.what());
  }
  const model::Model& m = s.model;
  s.plan = sim_models::make_sim_plan(c, m, where);
  const SimPlan& plan = s.plan;
  const urdf::ModelInterfaceSharedPtr urdf_model = urdf::parseURDFFile(c.urdf);
  if (!urdf_model) {
    throw std::runtime_error(c.urdf + ": urdfdom could not parse the file");
  }
  s.data.emplace(m);
  s.sense.emplace(m);
  s.n = m.n_joints;
  const int n = s.n;
  s.lower = Eigen::Map<const Eigen::VectorXd>(m.joint_lower.data(), n);
  s.upper = Eigen::Map<const Eigen::VectorXd>(m.joint_upper.data(), n);
  s.commands = sim_models::CommandHold(plan);
  s.tau = Eigen::VectorXd::Zero(m.nv);

  truth_ = GroundTruth{};
  static_cast<actuation::GroundTruth&>(truth_) = plan.initial_ground_truth();
  truth_.contact_points = contact_points(c, plan);
  if (c.place_on_ground && m.floating_base && !truth_.contact_points.empty()) {
    truth_.q[2] -=
        height_above_ground(m, *s.sense, truth_.q, truth_.contact_points, c.ground.height);
  }

  // ---- joint-limit springs: automatic stiffness from the mass-matrix diagonal ----
  const double h = o.step / o.substeps;
  // m_eff,j = 1/(M⁻¹)_jj: the inertia a torque on joint j alone meets, all
  // other joints and the base free (the smallest it can be).
  const Eigen::MatrixXd M_inv =
      model::mass_matrix(m, *s.sense, truth_.q).llt().solve(Eigen::MatrixXd::Identity(m.nv, m.nv));
  s.m_diag.resize(n);
  s.k_limit.resize(n);
  s.d_limit.resize(n);
  for (int j = 0; j < n; ++j) {
    const double mjj = 1.0 / M_inv(m.base_nv + j, m.base_nv + j);
    s.m_diag[j] = mjj;
    s.k_limit[j] =
        o.joint_limits.stiffness > 0.0 ? o.joint_limits.stiffness : mjj * (0.5 / h) * (0.5 / h);
    s.d_limit[j] = o.joint_limits.damping > 0.0 ? o.joint_limits.damping : mjj / h;
  }

  for (const auto& push : plan.pushes) {
    s.pushes.push_back(
        {sim_models::step_index(push.start, h), sim_models::step_index(push.end, h)});
  }
  s.wrenches.assign(plan.contact_links.size() + plan.pushes.size(), model::ExternalWrench{});
  for (std::size_t i = 0; i < plan.force_torque.size(); ++i) {
    s.fts.push_back(force_torque_model(c, plan, m, *urdf_model, i));
  }

  impl_ = std::move(impl);
  time_ = 0.0;
  step_count_ = 0;
  // One dynamics evaluation (nothing integrated) so that accelerations and
  // sensors are defined before the first step().
  compute_contacts();
  const Eigen::VectorXd& dnu = model::forward_dynamics(
      m, *impl_->data, truth_.q, truth_.nu, impl_->tau, config_.gravity,
      std::span<const model::ExternalWrench>(impl_->wrenches.data(), impl_->n_wrenches));
  truth_.dnu = dnu;
  compute_sensors_after_step();
  return plan.description;
}

void SimBackend::on_activate() {}

void SimBackend::on_deactivate() { impl_->commands.release(); }

void SimBackend::on_cleanup() {
  impl_.reset();
  truth_ = GroundTruth{};
  time_ = 0.0;
  step_count_ = 0;
}

void SimBackend::on_write(Time /*time*/, Duration /*period*/, const actuation::JointCommands& in) {
  impl_->commands.hold(in);
}

// Kinematics at (q, ν) into impl_->data, then the ground contact forces, summed
// per contact link into impl_->wrenches, and the active pushes appended. Updates
// the stick anchors (state of the tangential springs).
void SimBackend::compute_contacts() {
  Impl& s = *impl_;
  const model::Model& m = s.model;
  model::Data& d = *s.data;
  const robot_config::ContactModel& cc = config_.wbi.contact;
  const double ground = config_.ground.height;
  model::forward_velocity_kinematics(m, d, truth_.q, truth_.nu);
  for (auto& w : truth_.contact_wrenches) {
    w.setZero();
  }
  for (auto& cp : truth_.contact_points) {
    const auto fi = static_cast<std::size_t>(cp.frame);
    const auto b = static_cast<std::size_t>(m.frame_body[fi]);
    // the lowest point of the contact (its centre for a point)
    Vector3d p = d.p_WB[b] + d.R_WB[b] * (m.frame_R_BF[fi] * cp.p_F + m.frame_p_BF[fi]);
    p.z() -= cp.radius;
    const Vector3d v = d.v[b].head<3>() + d.v[b].tail<3>().cross(p);  // ṗ = v_O + ω × p
    cp.p_W = p;
    const double depth = ground - p.z();
    Vector3d f = Vector3d::Zero();
    if (depth > 0.0) {
      // normal: spring-damper, no adhesion
      const double fn = std::max(0.0, cc.stiffness * depth - cc.damping * v.z());
      Eigen::Vector2d ft = Eigen::Vector2d::Zero();
      cp.slipping = false;
      if (cc.tangential == robot_config::ContactModel::Tangential::kSpring) {
        if (!cp.in_contact) {
          cp.anchor = p.head<2>();
        }
        ft = -cc.tangential_stiffness * (p.head<2>() - cp.anchor) -
             cc.tangential_damping * v.head<2>();
        const double limit = cp.friction * fn;
        const double norm = ft.norm();
        if (norm > limit) {
          // slip: force on the cone, anchor dragged so that the spring alone gives it
          ft *= norm > 0.0 ? limit / norm : 0.0;
          cp.anchor = p.head<2>() + ft / cc.tangential_stiffness;
          cp.slipping = true;
        }
      } else {
        const Eigen::Vector2d vt = v.head<2>();
        ft = -cp.friction * fn * vt /
             std::sqrt(vt.squaredNorm() + cc.slip_velocity * cc.slip_velocity);
      }
      f << ft.x(), ft.y(), fn;
      cp.in_contact = true;
    } else {
      cp.in_contact = false;
      cp.slipping = false;
    }
    cp.force_W = f;
    // moment about the link frame origin
    const Vector3d p_F = d.p_WB[b] + d.R_WB[b] * m.frame_p_BF[fi];
    auto& w = truth_.contact_wrenches[static_cast<std::size_t>(cp.link)];
    w.head<3>() += f;
    w.tail<3>() += (p - p_F).cross(f);
  }
  std::size_t k = 0;
  for (std::size_t i = 0; i < truth_.contact_links.size(); ++i) {
    s.wrenches[k].frame = s.plan.contact_link_frames[i];
    s.wrenches[k].wrench = truth_.contact_wrenches[i];
    ++k;
  }
  for (std::size_t i = 0; i < s.pushes.size(); ++i) {
    Impl::Push& state = s.pushes[i];
    state.active = s.substep_count >= state.start && s.substep_count < state.end;
    Vector6d& truth = truth_.push_wrenches[i];
    truth.setZero();
    if (!state.active) {
      continue;
    }
    const SimPlan::Push& push = s.plan.pushes[i];
    const auto fi = static_cast<std::size_t>(push.frame);
    const auto b = static_cast<std::size_t>(m.frame_body[fi]);
    // about the link frame origin: r from it to the point, world axes
    const Vector3d r = d.R_WB[b] * (m.frame_R_BF[fi] * push.point);
    truth.head<3>() = push.force;
    truth.tail<3>() = r.cross(push.force);
    s.wrenches[k].frame = push.frame;
    s.wrenches[k].wrench = truth;
    ++k;
  }
  s.n_wrenches = k;
}

void SimBackend::substep(double h) {
  Impl& s = *impl_;
  const model::Model& m = s.model;
  compute_contacts();
  // joint torques: actuators, limits, damping and friction
  s.tau.setZero();
  const WbiOptions& c = config_.wbi;
  for (int j = 0; j < s.n; ++j) {
    const int iv = m.base_nv + j;
    const double qj = truth_.q[m.base_nq + j];
    const double dq = truth_.nu[iv];
    const double act = s.commands.actuate(j, dq);
    // limits: spring-damper beyond the limit, never pulling towards it
    double lim = 0.0;
    if (qj > s.upper[j]) {
      lim = std::min(0.0, -s.k_limit[j] * (qj - s.upper[j]) - s.d_limit[j] * dq);
    } else if (qj < s.lower[j]) {
      lim = std::max(0.0, -s.k_limit[j] * (qj - s.lower[j]) - s.d_limit[j] * dq);
    }
    // dissipation: viscous + smoothed Coulomb; never reverses q̇ within one substep
    const double diss = sim_models::dissipation_torque(dq, s.plan.damping[j], s.plan.friction[j],
                                                       c.friction_velocity, s.m_diag[j], h);
    s.tau[iv] = act + lim + diss;
  }
  const Eigen::VectorXd& dnu = model::forward_dynamics(
      m, *s.data, truth_.q, truth_.nu, s.tau, config_.gravity,
      std::span<const model::ExternalWrench>(s.wrenches.data(), s.n_wrenches));
  // semi-implicit Euler: ν first, then q with the new ν
  truth_.dnu = dnu;
  truth_.nu.noalias() += h * dnu;
  if (m.floating_base) {
    truth_.q.head<3>() += h * truth_.nu.head<3>();
    const Vector3d w = truth_.nu.segment<3>(3);
    const double angle = w.norm() * h;
    Eigen::Quaterniond dq;
    if (angle > 1e-12) {
      dq = Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / w.norm()));
    } else {
      dq = Eigen::Quaterniond(1.0, 0.5 * h * w.x(), 0.5 * h * w.y(), 0.5 * h * w.z());
    }
    Eigen::Quaterniond quat(truth_.q[3], truth_.q[4], truth_.q[5], truth_.q[6]);
    quat = (dq * quat).normalized();
    truth_.q[3] = quat.w();
    truth_.q[4] = quat.x();
    truth_.q[5] = quat.y();
    truth_.q[6] = quat.z();
  }
  truth_.q.tail(s.n).noalias() += h * truth_.nu.tail(s.n);
  for (int j = 0; j < s.n; ++j) {
    truth_.tau[j] = s.tau[m.base_nv + j];
  }
  truth_.tau_actuator = s.commands.torque();
}

void SimBackend::on_step() {
  const WbiOptions& o = config_.wbi;
  const double h = o.step / o.substeps;
  for (int k = 0; k < o.substeps; ++k) {
    substep(h);
    ++impl_->substep_count;
    time_ = static_cast<double>(step_count_) * o.step + static_cast<double>(k + 1) * h;
  }
  ++step_count_;
  time_ = static_cast<double>(step_count_) * o.step;
  compute_sensors_after_step();
}

// Ground-truth summaries and F/T wrenches from the dynamics of the last substep.
void SimBackend::compute_sensors_after_step() {
  Impl& s = *impl_;
  const model::Model& m = s.model;
  const model::Data& d = *s.data;
  truth_.time = time_;
  if (m.floating_base) {
    truth_.base_position = truth_.q.head<3>();
    truth_.base_orientation = truth_.q.segment<4>(3);
    truth_.base_velocity = truth_.nu.head<6>();
    truth_.base_acceleration = truth_.dnu.head<6>();
  }
  for (std::size_t i = 0; i < truth_.contact_links.size(); ++i) {
    const auto fi = static_cast<std::size_t>(s.plan.contact_link_frames[i]);
    const auto b = static_cast<std::size_t>(m.frame_body[fi]);
    truth_.contact_positions[i] = d.p_WB[b] + d.R_WB[b] * m.frame_p_BF[fi];
  }
  // F/T: wrench transmitted through the fixed joint = Newton–Euler of the part
  // beyond it:  f_J = Σ_b (I_b a_b + v_b ×* I_b v_b) − Σ w_ext   (world origin,
  // a_b includes −g), measured wrench (child on parent) = −f_J.
  for (std::size_t i = 0; i < s.fts.size(); ++i) {
    ForceTorqueModel& ft = s.fts[i];
    Vector6d f = Vector6d::Zero();
    for (std::size_t k = 0; k < ft.bodies.size(); ++k) {
      const auto b = static_cast<std::size_t>(ft.bodies[k]);
      const MassPiece& piece = ft.pieces[k];
      const model::SpatialInertia I = model::SpatialInertia::from_com(
          piece.m, d.p_WB[b] + d.R_WB[b] * piece.c, d.R_WB[b] * piece.I_c * d.R_WB[b].transpose());
      f += I * d.a[b] + model::cross_force(d.v[b], I * d.v[b]);
    }
    for (int li : ft.contact_links) {
      const auto fi =
          static_cast<std::size_t>(s.plan.contact_link_frames[static_cast<std::size_t>(li)]);
      const auto b = static_cast<std::size_t>(m.frame_body[fi]);
      const Vector3d p_F = d.p_WB[b] + d.R_WB[b] * m.frame_p_BF[fi];
      const Vector6d& w = truth_.contact_wrenches[static_cast<std::size_t>(li)];
      Vector6d wo = wrench_at_origin(w.head<3>(), p_F);
      wo.tail<3>() += w.tail<3>();
      f -= wo;
    }
    for (int pi : ft.pushes) {
      if (!s.pushes[static_cast<std::size_t>(pi)].active) {
        continue;
      }
      const SimPlan::Push& push = s.plan.pushes[static_cast<std::size_t>(pi)];
      const auto fi = static_cast<std::size_t>(push.frame);
      const auto b = static_cast<std::size_t>(m.frame_body[fi]);
      const Vector3d p = d.p_WB[b] + d.R_WB[b] * (m.frame_R_BF[fi] * push.point + m.frame_p_BF[fi]);
      f -= wrench_at_origin(push.force, p);
    }
    // child on parent, about the sensor origin, sensor axes
    const auto fi = static_cast<std::size_t>(s.plan.force_torque[i].frame);
    const auto b = static_cast<std::size_t>(m.frame_body[fi]);
    const Matrix3d R_WS = d.R_WB[b] * m.frame_R_BF[fi];
    const Vector3d p_S = d.p_WB[b] + d.R_WB[b] * m.frame_p_BF[fi];
    const Vector3d force = -f.head<3>();
    const Vector3d torque = -f.tail<3>() - p_S.cross(force);
    ft.wrench.head<3>() = R_WS.transpose() * force;
    ft.wrench.tail<3>() = R_WS.transpose() * torque;
  }
}

void SimBackend::on_read(Time /*time*/, Duration /*period*/, actuation::SensorReadings& out) {
  Impl& s = *impl_;
  const model::Model& m = s.model;
  for (int j = 0; j < s.n; ++j) {
    out.position[j] = truth_.q[m.base_nq + j];
    out.velocity[j] = truth_.nu[m.base_nv + j];
    out.torque[j] = truth_.tau_actuator[j];
    out.pwm[j] = s.commands.pwm()[j];
  }
  if (!s.plan.imus.empty()) {
    model::Data& k = *s.sense;
    model::forward_velocity_kinematics(m, k, truth_.q, truth_.nu);
    const model::Data& dyn = *s.data;  // accelerations of the last substep
    for (std::size_t i = 0; i < s.plan.imus.size(); ++i) {
      const auto fi = static_cast<std::size_t>(s.plan.imus[i].frame);
      const auto b = static_cast<std::size_t>(m.frame_body[fi]);
      const Matrix3d R_WF = k.R_WB[b] * m.frame_R_BF[fi];
      const Vector3d p = k.p_WB[b] + k.R_WB[b] * m.frame_p_BF[fi];
      const Vector3d w = k.v[b].tail<3>();
      const Vector3d pdot = k.v[b].head<3>() + w.cross(p);
      // p̈ − g = a_O + ω̇ × p + ω × ṗ  (a of the ABA includes −g)
      const Vector3d acc = dyn.a[b].head<3>() + dyn.a[b].tail<3>().cross(p) + w.cross(pdot);
      const Eigen::Quaterniond quat(R_WF);
      auto& r = out.imus[i];
      r.orientation << quat.w(), quat.x(), quat.y(), quat.z();
      r.gyro = R_WF.transpose() * w;
      r.accel = R_WF.transpose() * acc;
    }
  }
  for (std::size_t i = 0; i < s.fts.size(); ++i) {
    out.force_torque[i].wrench = s.fts[i].wrench;
  }
  s.noise.apply(out, stamp());
}

void SimBackend::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& nu) {
  const model::Model& m = model();
  if (q.size() != m.nq || nu.size() != m.nv) {
    throw std::invalid_argument("SimBackend::set_state: q must have " + std::to_string(m.nq) +
                                " and nu " + std::to_string(m.nv) + " elements");
  }
  truth_.q = q;
  truth_.nu = nu;
  for (auto& cp : truth_.contact_points) {
    cp.in_contact = false;
  }
  compute_sensors_after_step();
}

double SimBackend::mechanical_energy() {
  const model::Model& m = model();
  model::Data& k = *impl_->sense;
  const Eigen::MatrixXd& M = model::mass_matrix(m, k, truth_.q);
  const double kinetic = 0.5 * truth_.nu.dot(M * truth_.nu);
  const Vector3d& com = model::center_of_mass(m, k, truth_.q);
  const double potential = -m.total_mass * config_.gravity.dot(com);
  return kinetic + potential;
}

}  // namespace wbi::sim
