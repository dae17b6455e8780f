// make_sim_plan(): the robot config checked against the model and laid out as
// the tables of SimPlan (sim_plan.hpp).
#include "wbi/sim_models/sim_plan.hpp"

#include <algorithm>
#include <stdexcept>

namespace wbi::sim_models {

namespace {

using robot_config::RobotConfig;

// The joint table every engine offers: the model's names, order and limits,
// and the config's position gains.
actuation::BackendDescription joint_description(const model::Model& m, const RobotConfig& config) {
  actuation::BackendDescription d;
  d.robot = m.name;
  d.urdf = config.urdf;
  d.floating_base = m.floating_base;
  d.joint_names = m.joint_name;
  d.position_lower = m.joint_lower;
  d.position_upper = m.joint_upper;
  d.velocity_limit = m.joint_velocity_limit;
  d.effort_limit = m.joint_effort_limit;
  for (const auto& name : m.joint_name) {
    const auto joint = config.joints.find(name);
    const bool given = joint != config.joints.end();
    d.position_kp.push_back(given ? joint->second.kp : 0.0);
    d.position_kd.push_back(given ? joint->second.kd : 0.0);
    d.torque_sensor.push_back(config.joint_torque_sensors.has(name));
  }
  return d;
}

void plan_joints(const RobotConfig& c, const model::Model& m, SimPlan& plan) {
  const int n = m.n_joints;
  plan.n_joints = n;
  plan.nv = m.nv;
  plan.effort_limit.resize(n);
  plan.damping = Eigen::VectorXd::Zero(n);
  plan.friction = Eigen::VectorXd::Zero(n);
  plan.motors.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const auto js = static_cast<std::size_t>(j);
    plan.effort_limit[j] = m.joint_effort_limit[js];
    const robot_config::JointDynamics& dynamics = c.joints.at(m.joint_name[js]);
    plan.damping[j] = dynamics.damping;
    plan.friction[j] = dynamics.friction;
    plan.motors[js] = DcMotor::from(c.wbi.motor, plan.effort_limit[j]);
  }
  plan.description = joint_description(m, c);
}

void plan_initial_state(const RobotConfig& c, const model::Model& m, const std::string& where,
                        SimPlan& plan) {
  Eigen::VectorXd& q = plan.q0;
  q = Eigen::VectorXd::Zero(m.nq);
  if (m.floating_base) {
    if (!(c.initial_base_orientation.norm() > 0.0)) {
      throw std::invalid_argument(where + ": 'initial_base_orientation' must be non-zero");
    }
    q.head<3>() = c.initial_base_position;
    q.segment<4>(3) = c.initial_base_orientation.normalized();
  }
  for (const auto& [name, value] : c.initial_joint_positions) {
    if (!m.has_joint(name)) {
      throw std::invalid_argument(where + ": initial_joint_positions: unknown joint '" + name +
                                  "' in " + c.urdf);
    }
    q[m.base_nq + m.joint_id(name)] = value;
  }
}

}  // namespace

actuation::GroundTruth SimPlan::initial_ground_truth() const {
  actuation::GroundTruth truth;
  truth.q = q0;
  truth.nu = Eigen::VectorXd::Zero(nv);
  truth.dnu = Eigen::VectorXd::Zero(nv);
  truth.tau = Eigen::VectorXd::Zero(n_joints);
  truth.tau_actuator = Eigen::VectorXd::Zero(n_joints);
  truth.contact_links = contact_links;
  truth.contact_wrenches.assign(contact_links.size(), actuation::Vector6d::Zero());
  truth.contact_positions.assign(contact_links.size(), Eigen::Vector3d::Zero());
  for (const auto& push : pushes) {
    truth.push_links.push_back(push.link);
  }
  truth.push_wrenches.assign(pushes.size(), actuation::Vector6d::Zero());
  return truth;
}

SimPlan make_sim_plan(const RobotConfig& c, const model::Model& m, const std::string& where) {
  SimPlan plan;
  auto frame_of = [&](const std::string& link, const std::string& item) {
    if (!m.has_frame(link)) {
      throw std::invalid_argument(where + ": " + item + ": unknown link or frame '" + link +
                                  "' in " + c.urdf);
    }
    return m.frame_id(link);
  };
  for (const auto& joint : c.joint_torque_sensors.joints) {
    if (!m.has_joint(joint)) {
      throw std::invalid_argument(where + ": joint_torque_sensors: unknown joint '" + joint +
                                  "' in " + c.urdf);
    }
  }
  plan_joints(c, m, plan);
  plan_initial_state(c, m, where, plan);

  using Enable = robot_config::ContactModel::Enable;
  plan.contacts_on = c.wbi.contact.enable == Enable::kOn ||
                     (c.wbi.contact.enable == Enable::kAuto && m.floating_base);
  if (plan.contacts_on) {
    for (const auto& geometry : c.contacts) {
      auto it = std::find(plan.contact_links.begin(), plan.contact_links.end(), geometry.link);
      if (it == plan.contact_links.end()) {
        plan.contact_link_frames.push_back(frame_of(geometry.link, "contact"));
        plan.contact_links.push_back(geometry.link);
        it = plan.contact_links.end() - 1;
      }
      plan.contact_link_of.push_back(static_cast<int>(it - plan.contact_links.begin()));
    }
  }

  for (const auto& p : c.pushes) {
    SimPlan::Push push;
    push.link = p.link;
    push.frame = frame_of(p.link, "pushes");
    if (!(p.duration >= 0.0)) {
      throw std::invalid_argument(where + ": pushes: 'duration' must be >= 0");
    }
    push.start = p.start;
    push.end = p.start + p.duration;
    push.force = p.force;
    push.point = p.point;
    plan.pushes.push_back(push);
  }

  for (const auto& imu : c.imus) {
    plan.imus.push_back({frame_of(imu.frame, "imus '" + imu.name + "'")});
    plan.description.imu_names.push_back(imu.name);
    plan.description.imu_frames.push_back(imu.frame);
  }
  for (const auto& ft : c.force_torque) {
    const std::string item = "force_torque '" + ft.name + "'";
    // A fixed joint is no joint of the model: it survives as the frame of its child link.
    if (m.has_joint(ft.joint)) {
      throw std::invalid_argument(where + ": " + item + ": joint '" + ft.joint +
                                  "' is not a fixed joint");
    }
    const auto child = std::find(m.frame_joint.begin(), m.frame_joint.end(), ft.joint);
    if (ft.joint.empty() || child == m.frame_joint.end()) {
      throw std::invalid_argument(where + ": " + item + ": unknown joint '" + ft.joint + "' in " +
                                  c.urdf);
    }
    const auto frame = static_cast<std::size_t>(child - m.frame_joint.begin());
    plan.force_torque.push_back({static_cast<int>(frame), m.frame_name[frame]});
    plan.description.ft_names.push_back(ft.name);
    plan.description.ft_frames.push_back(m.frame_name[frame]);
  }
  return plan;
}

}  // namespace wbi::sim_models
