// MujocoBackend: MuJoCo behind SimulationBackend. Conventions and what each
// reading is: robot_side/mujoco_sim/README.md.
#include "wbi/mujoco_sim/mujoco_backend.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <wbi/sim_models/command_hold.hpp>
#include <wbi/sim_models/sensor_actuator_models.hpp>
#include <wbi/sim_models/sensor_noise.hpp>
#include <wbi/sim_models/sim_plan.hpp>

#include "wbi/mjcf/mjcf.hpp"
#include "wbi/mjcf/mujoco_conventions.hpp"
#include "wbi/mujoco_sim/load_mjcf.hpp"
#include "wbi/mujoco_sim/robot_mjcf.hpp"

namespace wbi::mujoco_sim {

using actuation::Duration;
using actuation::Time;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using MapVector = Eigen::Map<Eigen::VectorXd>;
using ConstMapVector = Eigen::Map<const Eigen::VectorXd>;

namespace {

int id_of(const mjModel* m, mjtObj type, const std::string& name) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) {
    throw std::logic_error("MujocoBackend: '" + name + "' missing from the written MJCF");
  }
  return id;
}

// Lowest z of a geom (box, sphere or capsule) at its current pose.
double lowest_z(const mjModel* m, const mjData* d, int g) {
  const mjtNum* R = d->geom_xmat + 9 * g;  // row-major, columns = geom axes in world
  const mjtNum* s = m->geom_size + 3 * g;
  const double z = d->geom_xpos[3 * g + 2];
  switch (m->geom_type[g]) {
    case mjGEOM_BOX:
      return z - std::abs(R[6]) * s[0] - std::abs(R[7]) * s[1] - std::abs(R[8]) * s[2];
    case mjGEOM_CAPSULE:
      return z - std::abs(R[8]) * s[1] - s[0];
    default:  // sphere
      return z - s[0];
  }
}

}  // namespace

struct MujocoBackend::Impl {
  model::Model model;
  sim_models::SimPlan plan;  // what the config asks, engine-neutral (sim_plan.hpp)
  std::string xml;
  mjModel* m = nullptr;
  mjData* d = nullptr;
  mjcf::MujocoIndex index;
  std::vector<int> dof_joint;  // [nv] MuJoCo dof → wbi joint (−1: the base)
  int n = 0;
  bool fresh_position = false;  // mj_step1 (or mj_forward) done at the current state

  // per joint
  sim_models::CommandHold commands;
  // Joint dissipation applied by us as a torque, the own plant's model: Coulomb
  // friction F_c (mujoco.joint_friction: torque) and, with the Euler integrator,
  // viscous damping (explicit: MuJoCo 2.2's Euler would integrate it implicitly
  // at the cost of a second factorisation of M + h·D per step); both bounded by
  // the effective inertia 1/(M⁻¹)_jj at the initial state. tau_dissipation =
  // the torque applied in the last step.
  bool friction_torque = false;
  Eigen::VectorXd friction, damping, m_eff, tau_dissipation;

  // contacts: geom → contact link (−1: none), and a site at each contact link's frame
  std::vector<int> geom_link;
  std::vector<int> link_site;

  struct Imu {
    int quat = 0, gyro = 0, accel = 0;  // sensordata addresses
  };
  std::vector<Imu> imus;
  struct Ft {
    int force = 0, torque = 0;  // sensordata addresses
  };
  std::vector<Ft> fts;
  struct Push {
    int site = 0, body = 0;
    std::int64_t start = 0, end = 0;  // MuJoCo steps: active for start ≤ k < end
    Vector3d force = Vector3d::Zero();
    Vector3d point = Vector3d::Zero();  // in the link frame (the site's axes are the link's)
    // The wrench of the last step: (force, moment about the link frame origin),
    // world axes; zero outside the window (ground truth).
    Vector6d applied = Vector6d::Zero();
  };
  std::vector<Push> pushes;
  std::int64_t mj_steps = 0;
  int bad_qacc = 0;  // MuJoCo's count of mjWARN_BADQACC (it resets the state on each)

  sim_models::SensorNoise noise;

  explicit Impl(const robot_config::RobotConfig& config) : noise(config) {}

  // The steps of configure(), in order.
  void load(const robot_config::RobotConfig& c, const std::string& where);
  void find_names(double timestep);
  void place_initial_state(const robot_config::RobotConfig& c);
  void measure_joint_inertias();
  void make_damping_explicit();

  ~Impl() {
    if (d != nullptr) {
      mj_deleteData(d);
    }
    if (m != nullptr) {
      mj_deleteModel(m);
    }
  }
};

// The MJCF of the config, loaded, with the options the writer leaves at
// MuJoCo's defaults.
void MujocoBackend::Impl::load(const robot_config::RobotConfig& c, const std::string& where) {
  const robot_config::MujocoOptions& o = c.mujoco;
  xml = mjcf::write_mjcf(model, robot_mjcf(c, model, plan).options);
  m = load_mjcf_from_memory(xml, {}, where + " " + c.urdf);
  m->opt.cone =
      o.cone == robot_config::MujocoOptions::Cone::kElliptic ? mjCONE_ELLIPTIC : mjCONE_PYRAMIDAL;
  m->opt.impratio = o.impratio;
  for (int g = 0; g < m->ngeom; ++g) {
    std::copy(o.solref.begin(), o.solref.end(), m->geom_solref + mjNREF * g);
    std::copy(o.solimp.begin(), o.solimp.end(), m->geom_solimp + mjNIMP * g);
  }
  d = mj_makeData(m);
}

// MuJoCo's ids and addresses of what the MJCF names (robot_mjcf.hpp).
// timestep: mujoco.timestep, the step of the push schedule.
void MujocoBackend::Impl::find_names(double timestep) {
  for (int j = 0; j < n; ++j) {
    const int id = id_of(m, mjOBJ_JOINT, model.joint_name[static_cast<std::size_t>(j)]);
    index.qpos.push_back(m->jnt_qposadr[id]);
    index.dof.push_back(m->jnt_dofadr[id]);
  }
  dof_joint.assign(static_cast<std::size_t>(m->nv), -1);
  for (int j = 0; j < n; ++j) {
    dof_joint[static_cast<std::size_t>(index.dof[static_cast<std::size_t>(j)])] = j;
  }
  geom_link.assign(static_cast<std::size_t>(m->ngeom), -1);
  for (std::size_t k = 0; k < plan.contact_link_of.size(); ++k) {
    geom_link[static_cast<std::size_t>(id_of(m, mjOBJ_GEOM, "wbi_contact_" + std::to_string(k)))] =
        plan.contact_link_of[k];
  }
  for (std::size_t l = 0; l < plan.contact_links.size(); ++l) {
    link_site.push_back(id_of(m, mjOBJ_SITE, "wbi_link_" + std::to_string(l)));
  }
  auto sensor = [&](const std::string& name) {
    return m->sensor_adr[id_of(m, mjOBJ_SENSOR, name)];
  };
  for (std::size_t i = 0; i < plan.imus.size(); ++i) {
    const std::string site = "wbi_imu_" + std::to_string(i);
    imus.push_back(
        {sensor(site + "_quat"), sensor(site + "_gyro"), sensor(site + "_accelerometer")});
  }
  for (std::size_t i = 0; i < plan.force_torque.size(); ++i) {
    const std::string site = "wbi_ft_" + std::to_string(i);
    fts.push_back({sensor(site + "_force"), sensor(site + "_torque")});
  }
  for (std::size_t i = 0; i < plan.pushes.size(); ++i) {
    const auto& p = plan.pushes[i];
    Push push;
    push.site = id_of(m, mjOBJ_SITE, "wbi_push_" + std::to_string(i));
    push.body = m->site_bodyid[push.site];
    push.start = sim_models::step_index(p.start, timestep);
    push.end = sim_models::step_index(p.end, timestep);
    push.force = p.force;
    push.point = p.point;
    pushes.push_back(push);
  }
}

// The plan's initial state, lowered onto the ground by its lowest contact geom
// when the config asks (place_on_ground).
void MujocoBackend::Impl::place_initial_state(const robot_config::RobotConfig& c) {
  mj_resetData(m, d);
  mjcf::wbi_q_to_mujoco_qpos(model, index, plan.q0, MapVector(d->qpos, m->nq));
  if (c.place_on_ground && model.floating_base && !plan.contact_link_of.empty()) {
    mj_kinematics(m, d);
    double z_min = std::numeric_limits<double>::infinity();
    for (int g = 0; g < m->ngeom; ++g) {
      if (geom_link[static_cast<std::size_t>(g)] >= 0) {
        z_min = std::min(z_min, lowest_z(m, d, g));
      }
    }
    d->qpos[2] -= z_min - c.ground.height;
  }
}

// Effective joint inertias 1/(M⁻¹)_jj at the current state (armature included).
void MujocoBackend::Impl::measure_joint_inertias() {
  std::vector<mjtNum> e(static_cast<std::size_t>(m->nv), 0.0), x(e.size(), 0.0);
  for (int j = 0; j < n; ++j) {
    const auto dof = static_cast<std::size_t>(index.dof[static_cast<std::size_t>(j)]);
    e[dof] = 1.0;
    mj_solveM(m, d, x.data(), e.data(), 1);
    e[dof] = 0.0;
    m_eff[j] = 1.0 / x[dof];
  }
}

// With Euler, viscous damping leaves MuJoCo's model (the written MJCF keeps
// it) for the explicit torque of apply_controls() when x = h·d/m_eff ≤ 0.1 on
// every joint: the explicit decay 1 − x per step is then as close to the exact
// e^−x as MuJoCo's implicit 1/(1 + x) (≈ x²/2 ≤ 0.5 %), and 5× below the bound
// of apply_controls() (x = ½), for m_eff changes with the posture. One joint
// above keeps MuJoCo's damping for all: it factorises M + h·D for one as for all.
void MujocoBackend::Impl::make_damping_explicit() {
  constexpr double kExplicitDamping = 0.1;
  for (int j = 0; j < n; ++j) {
    const int dof = index.dof[static_cast<std::size_t>(j)];
    if (m->opt.timestep * m->dof_damping[dof] > kExplicitDamping * m_eff[j]) {
      return;
    }
  }
  for (int j = 0; j < n; ++j) {
    mjtNum& dof_damping = m->dof_damping[index.dof[static_cast<std::size_t>(j)]];
    damping[j] = dof_damping;
    dof_damping = 0.0;
  }
}

MujocoBackend::MujocoBackend(robot_config::RobotConfig config) : config_(std::move(config)) {}
MujocoBackend::~MujocoBackend() = default;

const model::Model& MujocoBackend::model() const {
  if (!impl_) {
    throw std::logic_error("MujocoBackend::model(): configure() first");
  }
  return impl_->model;
}

const std::string& MujocoBackend::mjcf() const {
  if (!impl_) {
    throw std::logic_error("MujocoBackend::mjcf(): configure() first");
  }
  return impl_->xml;
}

Duration MujocoBackend::step_period() const {
  return Duration(std::llround(config_.mujoco.timestep * config_.mujoco.substeps * 1e9));
}

Time MujocoBackend::stamp() const { return Time(std::llround(time_ * 1e9)); }

actuation::BackendDescription MujocoBackend::on_configure() {
  const std::string where = "robot config (mujoco engine)";
  const robot_config::MujocoOptions& o = config_.mujoco;
  if (config_.urdf.empty()) {
    throw std::invalid_argument(where + ": 'urdf' is required");
  }
  if (!(o.timestep > 0.0) || o.substeps < 1) {
    throw std::invalid_argument(where +
                                ": 'mujoco.timestep' must be > 0 and 'mujoco.substeps' >= 1");
  }
  robot_config::complete_from_urdf(config_);
  const robot_config::RobotConfig& c = config_;
  auto impl = std::make_unique<Impl>(c);
  Impl& s = *impl;

  // ---- the model library's model, as `wbi model mjcf --robot-config` loads it ----
  s.model = robot_model(c);
  const model::Model& model = s.model;
  s.plan = sim_models::make_sim_plan(c, model, where);
  const sim_models::SimPlan& plan = s.plan;
  s.n = model.n_joints;
  const int n = s.n;

  s.load(c, where);
  s.find_names(o.timestep);
  // ---- joints: the held commands and the own plant's dissipation model ----
  s.commands = sim_models::CommandHold(plan);
  // Coulomb friction as a torque (mujoco.joint_friction: torque), else MuJoCo's rows.
  s.friction_torque = o.joint_friction == robot_config::MujocoOptions::JointFriction::kTorque;
  s.friction = s.friction_torque ? plan.friction : Eigen::VectorXd::Zero(n);
  s.damping = Eigen::VectorXd::Zero(n);
  s.m_eff = Eigen::VectorXd::Zero(n);
  s.tau_dissipation = Eigen::VectorXd::Zero(n);
  s.place_initial_state(c);
  // Every stage at the initial state: sensors and accelerations are defined
  // before the first step().
  mj_forward(s.m, s.d);
  s.fresh_position = true;
  s.measure_joint_inertias();
  if (s.m->opt.integrator == mjINT_EULER) {
    s.make_damping_explicit();
  }
  truth_ = plan.initial_ground_truth();
  impl_ = std::move(impl);
  time_ = 0.0;
  step_count_ = 0;
  collect_dynamics();
  collect_state();
  return plan.description;
}

void MujocoBackend::on_deactivate() { impl_->commands.release(); }

void MujocoBackend::on_cleanup() {
  impl_.reset();
  truth_ = actuation::GroundTruth{};
  time_ = 0.0;
  step_count_ = 0;
}

void MujocoBackend::on_write(Time /*time*/, Duration /*period*/,
                             const actuation::JointCommands& in) {
  impl_->commands.hold(in);
}

// Actuator torques (held commands, the PWM motor at the current velocity) into
// qfrc_applied, pushes into xfrc_applied. Needs the position stage (site poses).
void MujocoBackend::apply_controls() {
  Impl& s = *impl_;
  mjData* d = s.d;
  for (int j = 0; j < s.n; ++j) {
    const auto js = static_cast<std::size_t>(j);
    const int dof = s.index.dof[js];
    const double dq = d->qvel[dof];
    const double torque = s.commands.actuate(j, dq);
    // The own plant's viscous + smoothed Coulomb friction, bounded so that it
    // never reverses q̇ within one step (robot_side/sim): explicit, no constraint row.
    s.tau_dissipation[j] = sim_models::dissipation_torque(dq, s.damping[j], s.friction[j],
                                                          config_.wbi.friction_velocity, s.m_eff[j],
                                                          s.m->opt.timestep);
    d->qfrc_applied[dof] = torque + s.tau_dissipation[j];
  }
  // Pushes: force f at the point p → wrench (f, (p − c) × f) at the body's CoM c.
  for (const auto& push : s.pushes) {
    std::fill_n(d->xfrc_applied + 6 * push.body, 6, 0.0);
  }
  for (auto& push : s.pushes) {
    push.applied.setZero();
    if (s.mj_steps < push.start || s.mj_steps >= push.end) {
      continue;
    }
    const Eigen::Map<const Vector3d> p(d->site_xpos + 3 * push.site);
    const Eigen::Map<const Vector3d> com(d->xipos + 3 * push.body);
    Eigen::Map<Vector6d> w(d->xfrc_applied + 6 * push.body);
    w.head<3>() += push.force;
    w.tail<3>() += (p - com).cross(push.force);
    // For the ground truth, about the link frame origin p − R_WL·point.
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_WL(d->site_xmat +
                                                                              9 * push.site);
    push.applied.head<3>() = push.force;
    push.applied.tail<3>() = (R_WL * push.point).cross(push.force);
  }
}

void MujocoBackend::on_step() {
  Impl& s = *impl_;
  const mjModel* m = s.m;
  mjData* d = s.d;
  const bool rk4 = m->opt.integrator == mjINT_RK4;
  for (int k = 0; k < config_.mujoco.substeps; ++k) {
    if (rk4) {  // mj_step1/2 would integrate with Euler
      apply_controls();
      mj_step(m, d);
    } else {
      if (!s.fresh_position) {
        mj_step1(m, d);
      }
      apply_controls();
      mj_step2(m, d);
    }
    s.fresh_position = false;
    ++s.mj_steps;
    // MuJoCo answers a diverging step by resetting the state to the model's
    // reference pose and carrying on; a simulation that did is wrong, say so.
    if (d->warning[mjWARN_BADQACC].number != s.bad_qacc) {
      s.bad_qacc = d->warning[mjWARN_BADQACC].number;
      throw std::runtime_error(
          "MuJoCo: the simulation diverged (non-finite or huge acceleration at dof " +
          std::to_string(d->warning[mjWARN_BADQACC].lastinfo) + ", t = " + std::to_string(time_) +
          " s); MuJoCo reset the state. Lower the gains or the "
          "timestep (mujoco.timestep)");
    }
  }
  ++step_count_;
  time_ = static_cast<double>(step_count_) * config_.mujoco.timestep * config_.mujoco.substeps;
  // Contact forces, constraint torques and accelerations of the last MuJoCo step
  // (its start state), then positions and velocities (and their sensors) at the end.
  collect_dynamics();
  mj_step1(m, d);
  s.fresh_position = true;
  collect_state();
}

void MujocoBackend::collect_dynamics() {
  Impl& s = *impl_;
  const mjModel* m = s.m;
  const mjData* d = s.d;
  const model::Model& model = s.model;
  // ν̇ = Tᵀ qacc (Ṫν = 0, mujoco_conventions.hpp); the base rotation of that state
  mjcf::mujoco_qvel_to_wbi_nu(model, s.index, ConstMapVector(d->qpos, m->nq),
                              ConstMapVector(d->qacc, m->nv), truth_.dnu);
  if (model.floating_base) {
    truth_.base_acceleration = truth_.dnu.head<6>();
  }
  // Joint torque: actuator + dissipation torque + passive (MuJoCo's damping with
  // RK4 / implicit) + the joint's friction-loss and limit constraint forces
  // (scalar rows of J = ±1 on the joint's dof).
  for (int j = 0; j < s.n; ++j) {
    truth_.tau[j] = s.commands.torque()[j] + s.tau_dissipation[j] +
                    d->qfrc_passive[s.index.dof[static_cast<std::size_t>(j)]];
  }
  const bool sparse = mj_isSparse(m) != 0;
  for (int i = 0; i < d->nefc; ++i) {
    const int type = d->efc_type[i];
    if (type != mjCNSTR_FRICTION_DOF && type != mjCNSTR_LIMIT_JOINT) {
      continue;
    }
    const int dof = type == mjCNSTR_FRICTION_DOF ? d->efc_id[i] : m->jnt_dofadr[d->efc_id[i]];
    const double J = sparse ? d->efc_J[d->efc_J_rowadr[i]] : d->efc_J[i * m->nv + dof];
    const int j = s.dof_joint[static_cast<std::size_t>(dof)];
    if (j >= 0) {
      truth_.tau[j] += J * d->efc_force[i];
    }
  }
  truth_.tau_actuator = s.commands.torque();
  for (std::size_t i = 0; i < s.pushes.size(); ++i) {
    truth_.push_wrenches[i] = s.pushes[i].applied;
  }
  // Ground contact wrenches per contact link: (force, moment about the link
  // frame origin), world axes. mj_contactForce is in the contact frame (normal
  // first, from geom1 to geom2): the force on geom2; geom1 gets its opposite.
  for (auto& w : truth_.contact_wrenches) {
    w.setZero();
  }
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& con = d->contact[i];
    const int l1 = s.geom_link[static_cast<std::size_t>(con.geom1)];
    const int l2 = s.geom_link[static_cast<std::size_t>(con.geom2)];
    if (l1 < 0 && l2 < 0) {
      continue;
    }
    mjtNum local[6];
    mj_contactForce(m, d, i, local);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> frame(con.frame);
    const Vector3d f = frame.transpose() * Eigen::Map<const Vector3d>(local);
    const Eigen::Map<const Vector3d> p(con.pos);
    for (const auto& [link, sign] : {std::pair{l1, -1.0}, std::pair{l2, 1.0}}) {
      if (link < 0) {
        continue;
      }
      const auto li = static_cast<std::size_t>(link);
      const Eigen::Map<const Vector3d> origin(d->site_xpos + 3 * s.link_site[li]);
      truth_.contact_wrenches[li].head<3>() += sign * f;
      truth_.contact_wrenches[li].tail<3>() += (p - origin).cross(sign * f);
    }
  }
}

void MujocoBackend::collect_state() {
  Impl& s = *impl_;
  const mjModel* m = s.m;
  const mjData* d = s.d;
  const model::Model& model = s.model;
  const ConstMapVector qpos(d->qpos, m->nq);
  mjcf::mujoco_qpos_to_wbi_q(model, s.index, qpos, truth_.q);
  mjcf::mujoco_qvel_to_wbi_nu(model, s.index, qpos, ConstMapVector(d->qvel, m->nv), truth_.nu);
  truth_.time = time_;
  if (model.floating_base) {
    truth_.base_position = truth_.q.head<3>();
    truth_.base_orientation = truth_.q.segment<4>(3);
    truth_.base_velocity = truth_.nu.head<6>();
  }
  for (std::size_t l = 0; l < truth_.contact_positions.size(); ++l) {
    truth_.contact_positions[l] = Eigen::Map<const Vector3d>(d->site_xpos + 3 * s.link_site[l]);
  }
}

void MujocoBackend::on_read(Time /*time*/, Duration /*period*/, actuation::SensorReadings& out) {
  Impl& s = *impl_;
  const mjData* d = s.d;
  for (int j = 0; j < s.n; ++j) {
    const auto js = static_cast<std::size_t>(j);
    out.position[j] = d->qpos[s.index.qpos[js]];
    out.velocity[j] = d->qvel[s.index.dof[js]];
    out.torque[j] = s.commands.torque()[j];
    out.pwm[j] = s.commands.pwm()[j];
  }
  const mjtNum* data = d->sensordata;
  for (std::size_t i = 0; i < s.imus.size(); ++i) {
    const auto& imu = s.imus[i];
    auto& r = out.imus[i];
    r.orientation << data[imu.quat], data[imu.quat + 1], data[imu.quat + 2], data[imu.quat + 3];
    r.gyro = Eigen::Map<const Vector3d>(data + imu.gyro);
    r.accel = Eigen::Map<const Vector3d>(data + imu.accel);
  }
  // MuJoCo's force/torque: the parent on the child body; wbi's: the child side
  // on the parent side. Both about the sensor origin, in sensor axes.
  for (std::size_t i = 0; i < s.fts.size(); ++i) {
    const auto& ft = s.fts[i];
    auto& r = out.force_torque[i];
    r.wrench.head<3>() = -Eigen::Map<const Vector3d>(data + ft.force);
    r.wrench.tail<3>() = -Eigen::Map<const Vector3d>(data + ft.torque);
  }
  s.noise.apply(out, stamp());
}

}  // namespace wbi::mujoco_sim
