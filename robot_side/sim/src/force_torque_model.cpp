#include "force_torque_model.hpp"

#include <algorithm>
#include <set>

#include <Eigen/Geometry>

namespace wbi::sim {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

Matrix3d rotation_of(const urdf::Rotation& r) {
  return Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix();
}
Vector3d vector_of(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

// The links beyond a fixed joint: its child link and all the child's descendants.
std::set<std::string> links_beyond(const urdf::ModelInterface& urdf_model,
                                   const std::string& child_link) {
  std::set<std::string> beyond;
  std::vector<urdf::LinkConstSharedPtr> stack{urdf_model.getLink(child_link)};
  while (!stack.empty()) {
    const auto link = stack.back();
    stack.pop_back();
    beyond.insert(link->name);
    for (const auto& child : link->child_links) {
      stack.push_back(child);
    }
  }
  return beyond;
}

}  // namespace

void MassPiece::add(double m2, const Vector3d& c2, const Matrix3d& I2) {
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

ForceTorqueModel force_torque_model(const robot_config::RobotConfig& c,
                                    const sim_models::SimPlan& plan, const model::Model& m,
                                    const urdf::ModelInterface& urdf_model, std::size_t sensor) {
  ForceTorqueModel x;
  const std::set<std::string> beyond =
      links_beyond(urdf_model, plan.force_torque[sensor].child_link);
  for (const auto& name : beyond) {
    const auto link = urdf_model.getLink(name);
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
  for (std::size_t i = 0; i < plan.contact_links.size(); ++i) {
    if (beyond.count(plan.contact_links[i]) != 0) {
      x.contact_links.push_back(static_cast<int>(i));
    }
  }
  for (std::size_t i = 0; i < c.pushes.size(); ++i) {
    if (beyond.count(c.pushes[i].link) != 0) {
      x.pushes.push_back(static_cast<int>(i));
    }
  }
  return x;
}

}  // namespace wbi::sim
