// A robot config as MuJoCo is given it (robot_mjcf.hpp).
#include "wbi/mujoco_sim/robot_mjcf.hpp"

#include <algorithm>
#include <stdexcept>

#include <wbi/model/urdf.hpp>

namespace wbi::mujoco_sim {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

mjcf::ContactGeometry to_mjcf(const robot_config::ContactGeometry& g, const std::string& name) {
  mjcf::ContactGeometry out;
  out.name = name;
  out.link = g.link;
  out.shape = g.shape;
  out.size = g.size;
  out.radius = g.radius;
  out.length = g.length;
  out.position = g.position;
  out.rotation = g.rotation;
  out.friction = g.friction;
  return out;
}

}  // namespace

model::Model robot_model(const robot_config::RobotConfig& config) {
  model::LoadOptions load;
  load.fixed_base = config.fixed_base;
  load.armature = robot_config::armature_by_joint(config);
  load.repair_inertia = true;  // MuJoCo's compiler rejects non-physical inertias
  return model::load_urdf_file(config.urdf, load);
}

RobotMjcf robot_mjcf(const robot_config::RobotConfig& config, const model::Model& model,
                     const std::string& where) {
  return robot_mjcf(config, model, sim_models::make_sim_plan(config, model, where));
}

RobotMjcf robot_mjcf(const robot_config::RobotConfig& config, const model::Model& model,
                     const sim_models::SimPlan& plan) {
  RobotMjcf out;
  mjcf::MjcfOptions& mo = out.options;
  const robot_config::RobotConfig& c = config;
  const robot_config::MujocoOptions& o = c.mujoco;
  const int n = model.n_joints;
  mo.gravity = c.gravity;
  mo.timestep = o.timestep;
  mo.integrator = o.integrator;
  // Coulomb friction as MuJoCo's frictionloss rows, or none here: MujocoBackend
  // then applies the own plant's smoothed model as a torque (mujoco.joint_friction).
  const bool friction_rows =
      o.joint_friction == robot_config::MujocoOptions::JointFriction::kConstraint;
  for (int j = 0; j < n; ++j) {
    const auto& dyn = c.joints.at(model.joint_name[static_cast<std::size_t>(j)]);
    mo.armature.push_back(dyn.armature);
    mo.damping.push_back(dyn.damping);
    mo.frictionloss.push_back(friction_rows ? dyn.friction : 0.0);
  }
  // The ground and the contact geometry when the plan has contacts.
  if (plan.contacts_on) {
    // MuJoCo takes the larger friction of the two geoms: the ground's 0 lets
    // each contact's own μ (the ground's when it gives none) act, as in the own plant.
    mo.ground = {true, c.ground.height, 0.0};
    for (std::size_t l = 0; l < plan.contact_links.size(); ++l) {
      mo.sites.push_back({"wbi_link_" + std::to_string(l), plan.contact_links[l], Vector3d::Zero(),
                          Matrix3d::Identity(), mjcf::SiteSensor::kNone});
    }
    for (std::size_t k = 0; k < c.contacts.size(); ++k) {
      mo.contacts.push_back(to_mjcf(c.contacts[k], "wbi_contact_" + std::to_string(k)));
    }
  }
  for (std::size_t i = 0; i < c.imus.size(); ++i) {
    mo.sites.push_back({"wbi_imu_" + std::to_string(i), c.imus[i].frame, Vector3d::Zero(),
                        Matrix3d::Identity(), mjcf::SiteSensor::kImu});
  }
  for (std::size_t i = 0; i < plan.force_torque.size(); ++i) {
    const std::string& child_link = plan.force_torque[i].child_link;
    // The child side as a body of its own, so that MuJoCo's force/torque
    // sensors measure across the joint.
    if (std::find(mo.welded_links.begin(), mo.welded_links.end(), child_link) ==
        mo.welded_links.end()) {
      mo.welded_links.push_back(child_link);
    }
    mo.sites.push_back({"wbi_ft_" + std::to_string(i), child_link, Vector3d::Zero(),
                        Matrix3d::Identity(), mjcf::SiteSensor::kForceTorque});
  }
  for (std::size_t i = 0; i < c.pushes.size(); ++i) {
    mo.sites.push_back({"wbi_push_" + std::to_string(i), c.pushes[i].link, c.pushes[i].point,
                        Matrix3d::Identity(), mjcf::SiteSensor::kNone});
  }
  return out;
}

}  // namespace wbi::mujoco_sim
