// What a configuration leaves out, from its URDF: joint dynamics and contact boxes.
#include <algorithm>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>
#include <Eigen/Geometry>

#include "wbi/robot_config/robot_config.hpp"

namespace wbi::robot_config {

void complete_from_urdf(RobotConfig& config) {
  const urdf::ModelInterfaceSharedPtr tree = urdf::parseURDFFile(config.urdf);
  if (!tree) {
    throw std::runtime_error(config.urdf + ": urdfdom could not parse the URDF");
  }
  // Movable joints (the model's), in name order: their <dynamics>, no armature.
  for (const auto& [name, joint] : tree->joints_) {
    const bool movable = joint->type == urdf::Joint::REVOLUTE ||
                         joint->type == urdf::Joint::CONTINUOUS ||
                         joint->type == urdf::Joint::PRISMATIC;
    if (!movable || config.joints.count(name) != 0) {
      continue;
    }
    JointDynamics j;
    if (joint->dynamics) {
      j.damping = joint->dynamics->damping;
      j.friction = joint->dynamics->friction;
    }
    config.joints[name] = j;
  }
  // <collision> boxes, links in name order (urdfdom's map): deterministic.
  if (config.contacts.empty()) {
    for (const auto& [link_name, link] : tree->links_) {
      for (const auto& collision : link->collision_array) {
        if (!collision || !collision->geometry ||
            collision->geometry->type != urdf::Geometry::BOX) {
          continue;
        }
        const auto box = std::dynamic_pointer_cast<urdf::Box>(collision->geometry);
        const auto& o = collision->origin;
        ContactGeometry g;
        g.link = link_name;
        g.shape = wbi::ContactShape::box;
        g.size = Eigen::Vector3d(box->dim.x, box->dim.y, box->dim.z);
        g.position = Eigen::Vector3d(o.position.x, o.position.y, o.position.z);
        g.rotation = Eigen::Quaterniond(o.rotation.w, o.rotation.x, o.rotation.y, o.rotation.z)
                         .normalized()
                         .toRotationMatrix();
        config.contacts.push_back(g);
      }
    }
  }
  for (auto& contact : config.contacts) {
    if (contact.friction < 0.0) {
      contact.friction = config.ground.friction;
    }
  }
}

bool JointTorqueSensors::has(const std::string& joint) const {
  switch (which) {
    case Which::kAll:
      return true;
    case Which::kNone:
      return false;
    case Which::kListed:
      break;
  }
  return std::find(joints.begin(), joints.end(), joint) != joints.end();
}

std::map<std::string, double> armature_by_joint(const RobotConfig& config) {
  std::map<std::string, double> armature;
  for (const auto& [name, joint] : config.joints) {
    armature[name] = joint.armature;
  }
  return armature;
}

}  // namespace wbi::robot_config
