// SimBackend: the plant. Models and formulas: components/sim/README.md.
#include "wbi/sim/sim_backend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <span>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <wbi/sim_models/sensor_actuator_models.hpp>

#include "wbi/model/aba.hpp"
#include "wbi/model/com.hpp"
#include "wbi/model/crba.hpp"
#include "wbi/model/kinematics.hpp"
#include "wbi/model/urdf.hpp"

namespace wbi::sim {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using actuation::OutputMode;
// The models every engine shares.
using sim_models::actuator_output;
using sim_models::ActuatorOutput;
using sim_models::DcMotor;
using sim_models::encoder_step;
using sim_models::Gaussian;
using sim_models::joint_description;
using sim_models::quantise;

namespace {

Matrix3d rotation_of(const urdf::Rotation& r) {
  return Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
}
Vector3d vector_of(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

// Mass, CoM and rotational inertia about the CoM, in some body's axes.
struct MassPiece {
  double m = 0.0;
  Vector3d c = Vector3d::Zero();
  Matrix3d I_c = Matrix3d::Zero();
  void add(double m2, const Vector3d& c2, const Matrix3d& I2) {
    if (m2 <= 0.0) {
      return;
    }
    const double mt = m + m2;
    const Vector3d ct = (m * c + m2 * c2) / mt;
    auto shift = [](double mass, const Vector3d& d) {
      return Matrix3d(mass * (d.squaredNorm() * Matrix3d::Identity() - d * d.transpose()));
    };
    I_c = I_c + shift(m, c - ct) + I2 + shift(m2, c2 - ct);
    m = mt;
    c = ct;
  }
};

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
  std::optional<model::Data> data;   // dynamics (substeps)
  std::optional<model::Data> sense;  // kinematics for read() and helpers
  int n = 0;                         // joints

  // ---- per joint (size n) ----
  Eigen::VectorXd damping, friction, lower, upper, effort, m_diag, k_limit, d_limit;
  std::vector<DcMotor> motor;  // PWM commands
  std::vector<OutputMode> cmd_mode;
  Eigen::VectorXd cmd_value;
  Eigen::VectorXd tau;      // [nv] joint-space generalized force of the substep
  Eigen::VectorXd tau_act;  // [n] actuator torque of the substep
  Eigen::VectorXd pwm;      // [n] motor duty of the substep (PWM mode: the command; else the
                            //     duty the motor model needs for the actuator torque)

  // ---- contacts ----
  std::vector<int> contact_link_frame;          // [n_links]
  std::vector<model::ExternalWrench> wrenches;  // [n_links + n_pushes], used prefix n_wrenches
  std::size_t n_wrenches = 0;
  bool contacts_on = false;

  // ---- sensors ----
  struct Imu {
    int frame = 0;
    double gyro_noise = 0.0, accel_noise = 0.0;
  };
  std::vector<Imu> imus;
  struct Ft {
    int frame = 0;                   // sensor frame
    std::vector<int> bodies;         // bodies with mass beyond the joint
    std::vector<MassPiece> pieces;   // their mass beyond the joint, in body axes
    std::vector<int> contact_links;  // contact links beyond the joint
    std::vector<int> pushes;         // pushes on links beyond the joint
    double force_noise = 0.0, torque_noise = 0.0;
    Vector6d wrench = Vector6d::Zero();  // latest, sensor frame
  };
  std::vector<Ft> fts;

  struct Push {
    int frame = 0;
    std::int64_t start = 0, end = 0;  // substep indices: active for start ≤ k < end
    Vector3d force = Vector3d::Zero();
    Vector3d point = Vector3d::Zero();
    bool active = false;
  };
  std::vector<Push> pushes;

  Gaussian noise{0};
  std::int64_t substep_count = 0;  // substeps done since configure()
  double encoder_step = 0.0;
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
  auto impl = std::make_unique<Impl>();
  Impl& s = *impl;
  model::LoadOptions options;
  options.fixed_base = c.fixed_base;
  robot_config::complete_from_urdf(config_);  // every joint's dynamics, URDF boxes if no contacts
  options.armature = robot_config::armature_by_joint(c);
  try {
    s.model = model::load_urdf_file(c.urdf, options);
  } catch (const std::invalid_argument& error) {  // a joints: entry; name the key
    throw std::invalid_argument(where + ": joints: " + error.what());
  }
  const urdf::ModelInterfaceSharedPtr urdf_model = urdf::parseURDFFile(c.urdf);
  if (!urdf_model) {
    throw std::runtime_error(c.urdf + ": urdfdom could not parse the file");
  }
  const model::Model& m = s.model;
  s.data.emplace(m);
  s.sense.emplace(m);
  s.n = m.n_joints;
  const int n = s.n;
  auto frame_of = [&](const std::string& link, const std::string& what) {
    if (!m.has_frame(link)) {
      throw std::invalid_argument(where + ": " + what + ": unknown link or frame '" + link +
                                  "' in " + c.urdf);
    }
    return m.frame_id(link);
  };

  // ---- joints: limits, passive dynamics (robot config), motors ----
  s.damping = Eigen::VectorXd::Zero(n);
  s.friction = Eigen::VectorXd::Zero(n);
  s.lower.resize(n);
  s.upper.resize(n);
  s.effort.resize(n);
  s.motor.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const auto& name = m.joint_name[static_cast<std::size_t>(j)];
    s.lower[j] = m.joint_lower[static_cast<std::size_t>(j)];
    s.upper[j] = m.joint_upper[static_cast<std::size_t>(j)];
    s.effort[j] = m.joint_effort_limit[static_cast<std::size_t>(j)];
    const robot_config::JointDynamics& dynamics = c.joints.at(name);
    s.damping[j] = dynamics.damping;
    s.friction[j] = dynamics.friction;
    s.motor[static_cast<std::size_t>(j)] = DcMotor::from(o.motor, s.effort[j]);
  }
  s.cmd_mode.assign(static_cast<std::size_t>(n), OutputMode::kIdle);
  s.cmd_value = Eigen::VectorXd::Zero(n);
  s.tau = Eigen::VectorXd::Zero(m.nv);
  s.tau_act = Eigen::VectorXd::Zero(n);
  s.pwm = Eigen::VectorXd::Zero(n);

  // ---- initial state ----
  Eigen::VectorXd q = Eigen::VectorXd::Zero(m.nq);
  if (m.floating_base) {
    q.head<3>() = c.initial_base_position;
    Eigen::Vector4d quat = c.initial_base_orientation;
    if (!(quat.norm() > 0.0)) {
      throw std::invalid_argument(where + ": 'initial_base_orientation' must be non-zero");
    }
    q.segment<4>(3) = quat.normalized();
  }
  for (const auto& [name, value] : c.initial_joint_positions) {
    if (!m.has_joint(name)) {
      throw std::invalid_argument(where + ": initial_joint_positions: unknown joint '" + name +
                                  "' in " + c.urdf);
    }
    q[m.base_nq + m.joint_id(name)] = value;
  }

  // ---- contact points ----
  using robot_config::ContactModel;
  s.contacts_on = o.contact.enable == ContactModel::Enable::kOn ||
                  (o.contact.enable == ContactModel::Enable::kAuto && m.floating_base);
  truth_ = GroundTruth{};
  if (s.contacts_on) {
    auto link_index = [&](const std::string& link) {
      for (std::size_t i = 0; i < truth_.contact_links.size(); ++i) {
        if (truth_.contact_links[i] == link) {
          return static_cast<int>(i);
        }
      }
      truth_.contact_links.push_back(link);
      s.contact_link_frame.push_back(frame_of(link, "contact"));
      return static_cast<int>(truth_.contact_links.size() - 1);
    };
    // Box: the 4 corners of its −z face; sphere: its centre with its radius;
    // capsule: its two end spheres.
    for (const auto& g : c.contacts) {
      const int li = link_index(g.link);
      auto add = [&](const Vector3d& p_F, double radius) {
        ContactPoint cp;
        cp.link = li;
        cp.frame = s.contact_link_frame[static_cast<std::size_t>(li)];
        cp.p_F = p_F;
        cp.radius = radius;
        cp.friction = g.friction;
        truth_.contact_points.push_back(cp);
      };
      switch (g.shape) {
        case wbi::ContactShape::box:
          for (int sx : {1, -1}) {
            for (int sy : {1, -1}) {
              add(g.position + g.rotation * Vector3d(0.5 * sx * g.size.x(), 0.5 * sy * g.size.y(),
                                                     -0.5 * g.size.z()),
                  0.0);
            }
          }
          break;
        case wbi::ContactShape::sphere:
          add(g.position, g.radius);
          break;
        case wbi::ContactShape::capsule:
          for (int sz : {1, -1}) {
            add(g.position + g.rotation * Vector3d(0.0, 0.0, 0.5 * sz * g.length), g.radius);
          }
          break;
      }
    }
  }
  truth_.contact_wrenches.assign(truth_.contact_links.size(), Vector6d::Zero());
  truth_.contact_positions.assign(truth_.contact_links.size(), Vector3d::Zero());

  // place on the ground: lowest contact point on the ground
  if (c.place_on_ground && m.floating_base && !truth_.contact_points.empty()) {
    model::forward_kinematics(m, *s.sense, q);
    double z_min = std::numeric_limits<double>::infinity();
    for (const auto& cp : truth_.contact_points) {
      const auto fi = static_cast<std::size_t>(cp.frame);
      const auto b = static_cast<std::size_t>(m.frame_body[fi]);
      const Vector3d p =
          s.sense->p_WB[b] + s.sense->R_WB[b] * (m.frame_R_BF[fi] * cp.p_F + m.frame_p_BF[fi]);
      z_min = std::min(z_min, p.z() - cp.radius);
    }
    q[2] -= z_min - c.ground.height;
  }

  // ---- joint-limit springs: automatic stiffness from the mass-matrix diagonal ----
  const double h = o.step / o.substeps;
  // m_eff,j = 1/(M⁻¹)_jj: the inertia a torque on joint j alone meets, all
  // other joints and the base free (the smallest it can be).
  const Eigen::MatrixXd M_inv =
      model::mass_matrix(m, *s.sense, q).llt().solve(Eigen::MatrixXd::Identity(m.nv, m.nv));
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

  // ---- pushes ----
  for (const auto& p : c.pushes) {
    Impl::Push push;
    push.frame = frame_of(p.link, "pushes");
    push.start = std::llround(p.start / h);
    push.end = std::llround((p.start + p.duration) / h);
    push.force = p.force;
    push.point = p.point;
    if (!(p.duration >= 0.0)) {
      throw std::invalid_argument(where + ": pushes: 'duration' must be >= 0");
    }
    s.pushes.push_back(push);
  }
  s.wrenches.assign(truth_.contact_links.size() + s.pushes.size(), model::ExternalWrench{});

  // ---- sensors ----
  actuation::BackendDescription d = joint_description(m, c);
  for (const auto& imu : c.imus) {
    Impl::Imu x;
    x.frame = frame_of(imu.frame, "imus '" + imu.name + "'");
    x.gyro_noise = imu.gyro_noise;
    x.accel_noise = imu.accel_noise;
    s.imus.push_back(x);
    d.imu_names.push_back(imu.name);
    d.imu_frames.push_back(imu.frame);
  }
  for (const auto& ft : c.force_torque) {
    const auto uj = urdf_model->getJoint(ft.joint);
    if (!uj) {
      throw std::invalid_argument(where + ": force_torque '" + ft.name + "': unknown joint '" +
                                  ft.joint + "' in " + c.urdf);
    }
    if (uj->type != urdf::Joint::FIXED) {
      throw std::invalid_argument(where + ": force_torque '" + ft.name + "': joint '" + ft.joint +
                                  "' is not a fixed joint");
    }
    Impl::Ft x;
    x.frame = frame_of(uj->child_link_name, "force_torque '" + ft.name + "'");
    x.force_noise = ft.force_noise;
    x.torque_noise = ft.torque_noise;
    // Links beyond the joint: the child link and all its descendants.
    std::set<std::string> beyond;
    std::vector<urdf::LinkConstSharedPtr> stack{urdf_model->getLink(uj->child_link_name)};
    while (!stack.empty()) {
      const auto link = stack.back();
      stack.pop_back();
      beyond.insert(link->name);
      for (const auto& child : link->child_links) {
        stack.push_back(child);
      }
    }
    for (const auto& name : beyond) {
      const auto link = urdf_model->getLink(name);
      if (!link->inertial || link->inertial->mass <= 0.0) {
        continue;
      }
      const auto fi = static_cast<std::size_t>(m.frame_id(name));
      const int body = m.frame_body[fi];
      const auto& in = *link->inertial;
      const Matrix3d R_LI = rotation_of(in.origin.rotation);
      Matrix3d I_I;
      I_I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      const Matrix3d R_BI = m.frame_R_BF[fi] * R_LI;
      const Vector3d c_B = m.frame_p_BF[fi] + m.frame_R_BF[fi] * vector_of(in.origin.position);
      auto it = std::find(x.bodies.begin(), x.bodies.end(), body);
      if (it == x.bodies.end()) {
        x.bodies.push_back(body);
        x.pieces.emplace_back();
        it = x.bodies.end() - 1;
      }
      x.pieces[static_cast<std::size_t>(it - x.bodies.begin())].add(in.mass, c_B,
                                                                    R_BI * I_I * R_BI.transpose());
    }
    for (std::size_t i = 0; i < truth_.contact_links.size(); ++i) {
      if (beyond.count(truth_.contact_links[i]) != 0) {
        x.contact_links.push_back(static_cast<int>(i));
      }
    }
    for (std::size_t i = 0; i < c.pushes.size(); ++i) {
      if (beyond.count(c.pushes[i].link) != 0) {
        x.pushes.push_back(static_cast<int>(i));
      }
    }
    s.fts.push_back(std::move(x));
    d.ft_names.push_back(ft.name);
    d.ft_frames.push_back(uj->child_link_name);
  }

  s.noise = Gaussian(o.seed);
  s.encoder_step = encoder_step(o.encoders);

  // ---- ground truth buffers ----
  truth_.q = q;
  truth_.nu = Eigen::VectorXd::Zero(m.nv);
  truth_.dnu = Eigen::VectorXd::Zero(m.nv);
  truth_.tau = Eigen::VectorXd::Zero(n);
  truth_.tau_actuator = Eigen::VectorXd::Zero(n);
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
  return d;
}

void SimBackend::on_activate() {}

void SimBackend::on_deactivate() {
  impl_->cmd_mode.assign(impl_->cmd_mode.size(), OutputMode::kIdle);
  impl_->cmd_value.setZero();
}

void SimBackend::on_cleanup() {
  impl_.reset();
  truth_ = GroundTruth{};
  time_ = 0.0;
  step_count_ = 0;
}

void SimBackend::on_write(Time /*time*/, Duration /*period*/, const actuation::JointCommands& in) {
  Impl& s = *impl_;
  for (int j = 0; j < s.n; ++j) {
    s.cmd_mode[static_cast<std::size_t>(j)] = in.mode[static_cast<std::size_t>(j)];
    s.cmd_value[j] = in.value[j];
  }
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
    s.wrenches[k].frame = s.contact_link_frame[i];
    s.wrenches[k].wrench = truth_.contact_wrenches[i];
    ++k;
  }
  for (auto& push : s.pushes) {
    push.active = s.substep_count >= push.start && s.substep_count < push.end;
    if (!push.active) {
      continue;
    }
    const auto fi = static_cast<std::size_t>(push.frame);
    const auto b = static_cast<std::size_t>(m.frame_body[fi]);
    const Vector3d r = d.R_WB[b] * (m.frame_R_BF[fi] * push.point);
    s.wrenches[k].frame = push.frame;
    s.wrenches[k].wrench.head<3>() = push.force;
    s.wrenches[k].wrench.tail<3>() = r.cross(push.force);
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
    const ActuatorOutput out =
        actuator_output(s.cmd_mode[static_cast<std::size_t>(j)], s.cmd_value[j], dq,
                        s.motor[static_cast<std::size_t>(j)], s.effort[j]);
    const double act = out.torque;
    s.tau_act[j] = act;
    s.pwm[j] = out.pwm;
    // limits: spring-damper beyond the limit, never pulling towards it
    double lim = 0.0;
    if (qj > s.upper[j]) {
      lim = std::min(0.0, -s.k_limit[j] * (qj - s.upper[j]) - s.d_limit[j] * dq);
    } else if (qj < s.lower[j]) {
      lim = std::max(0.0, -s.k_limit[j] * (qj - s.lower[j]) - s.d_limit[j] * dq);
    }
    // dissipation: viscous + smoothed Coulomb; never reverses q̇ within one substep
    double diss = -s.damping[j] * dq - s.friction[j] * std::tanh(dq / c.friction_velocity);
    const double max_diss = 0.5 * s.m_diag[j] * std::abs(dq) / h;
    diss = std::clamp(diss, -max_diss, max_diss);
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
  truth_.tau_actuator = s.tau_act;
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
    const auto fi = static_cast<std::size_t>(s.contact_link_frame[i]);
    const auto b = static_cast<std::size_t>(m.frame_body[fi]);
    truth_.contact_positions[i] = d.p_WB[b] + d.R_WB[b] * m.frame_p_BF[fi];
  }
  // F/T: wrench transmitted through the fixed joint = Newton–Euler of the part
  // beyond it:  f_J = Σ_b (I_b a_b + v_b ×* I_b v_b) − Σ w_ext   (world origin,
  // a_b includes −g), measured wrench (child on parent) = −f_J.
  for (auto& ft : s.fts) {
    Vector6d f = Vector6d::Zero();
    for (std::size_t k = 0; k < ft.bodies.size(); ++k) {
      const auto b = static_cast<std::size_t>(ft.bodies[k]);
      const MassPiece& piece = ft.pieces[k];
      const model::SpatialInertia I = model::SpatialInertia::from_com(
          piece.m, d.p_WB[b] + d.R_WB[b] * piece.c, d.R_WB[b] * piece.I_c * d.R_WB[b].transpose());
      f += I * d.a[b] + model::cross_force(d.v[b], I * d.v[b]);
    }
    for (int li : ft.contact_links) {
      const auto fi = static_cast<std::size_t>(s.contact_link_frame[static_cast<std::size_t>(li)]);
      const auto b = static_cast<std::size_t>(m.frame_body[fi]);
      const Vector3d p_F = d.p_WB[b] + d.R_WB[b] * m.frame_p_BF[fi];
      const Vector6d& w = truth_.contact_wrenches[static_cast<std::size_t>(li)];
      Vector6d wo = wrench_at_origin(w.head<3>(), p_F);
      wo.tail<3>() += w.tail<3>();
      f -= wo;
    }
    for (int pi : ft.pushes) {
      const auto& push = s.pushes[static_cast<std::size_t>(pi)];
      if (!push.active) {
        continue;
      }
      const auto fi = static_cast<std::size_t>(push.frame);
      const auto b = static_cast<std::size_t>(m.frame_body[fi]);
      const Vector3d p = d.p_WB[b] + d.R_WB[b] * (m.frame_R_BF[fi] * push.point + m.frame_p_BF[fi]);
      f -= wrench_at_origin(push.force, p);
    }
    // child on parent, about the sensor origin, sensor axes
    const auto fi = static_cast<std::size_t>(ft.frame);
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
  const robot_config::EncoderConfig& enc = config_.wbi.encoders;
  const Time stamp_now = stamp();
  for (int j = 0; j < s.n; ++j) {
    const double qj = truth_.q[m.base_nq + j];
    const double dq = truth_.nu[m.base_nv + j];
    out.position[j] = quantise(qj + s.noise(enc.position_noise), s.encoder_step);
    out.velocity[j] = dq + s.noise(enc.velocity_noise);
    const double tau = truth_.tau_actuator[j];
    out.torque[j] = tau + s.noise(enc.torque_noise);
    out.pwm[j] = s.pwm[j];
  }
  out.joint_stamp = stamp_now;
  if (!s.imus.empty()) {
    model::Data& k = *s.sense;
    model::forward_velocity_kinematics(m, k, truth_.q, truth_.nu);
    const model::Data& dyn = *s.data;  // accelerations of the last substep
    for (std::size_t i = 0; i < s.imus.size(); ++i) {
      const auto& imu = s.imus[i];
      const auto fi = static_cast<std::size_t>(imu.frame);
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
      const Vector3d gyro = R_WF.transpose() * w;
      const Vector3d accel = R_WF.transpose() * acc;
      for (int a = 0; a < 3; ++a) {
        r.gyro[a] = gyro[a] + s.noise(imu.gyro_noise);
        r.accel[a] = accel[a] + s.noise(imu.accel_noise);
      }
      r.stamp = stamp_now;
    }
  }
  for (std::size_t i = 0; i < s.fts.size(); ++i) {
    const auto& ft = s.fts[i];
    auto& r = out.force_torque[i];
    for (int a = 0; a < 3; ++a) {
      r.wrench[a] = ft.wrench[a] + s.noise(ft.force_noise);
      r.wrench[a + 3] = ft.wrench[a + 3] + s.noise(ft.torque_noise);
    }
    r.stamp = stamp_now;
  }
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
