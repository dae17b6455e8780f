// URDF → Model. The XML is first read with tinyxml2 to report syntax errors
// with their line and to check the tree structure (one root, no loops, no
// dangling links; urdf_structure.cpp); urdfdom then provides the values, whose
// inertias are checked or repaired (urdf_inertia.cpp).
#include "wbi/model/urdf.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "joint.hpp"
#include "urdf_detail.hpp"

namespace wbi::model {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Placement {
  Matrix3d R = Matrix3d::Identity();
  Vector3d p = Vector3d::Zero();
  Placement operator*(const Placement& o) const { return {R * o.R, p + R * o.p}; }
};

Placement to_placement(const urdf::Pose& pose) {
  Placement x;
  x.p = Vector3d(pose.position.x, pose.position.y, pose.position.z);
  x.R = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
            .normalized()
            .toRotationMatrix();
  return x;
}

using detail::check_inertial;
using detail::check_structure;
using detail::Error;
using detail::RawJoint;
using detail::repair_inertia;

struct Builder {
  const urdf::ModelInterface& urdf;
  const std::map<std::string, RawJoint>& raw;
  const LoadOptions& options;
  const Error& err;
  Model model;
  std::vector<SpatialInertia> acc;  // per body, about the body origin, body axes
  std::set<std::string> kept;       // joints that move (reduced model), empty: all
  std::map<std::string, int> joint_to_body;

  bool moves(const urdf::Joint& j) const {
    const bool movable = j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS ||
                         j.type == urdf::Joint::PRISMATIC;
    return movable && (options.joints.empty() || kept.count(j.name) > 0);
  }

  void add_link(const urdf::Link& link, int body, const Placement& X_BL, int parent_frame) {
    const int frame = static_cast<int>(model.frame_name.size());
    model.frame_name.push_back(link.name);
    model.frame_body.push_back(body);
    model.frame_R_BF.push_back(X_BL.R);
    model.frame_p_BF.push_back(X_BL.p);
    model.frame_parent.push_back(parent_frame);
    model.frame_joint.push_back(link.parent_joint ? link.parent_joint->name : std::string());
    model.frame_inertia.emplace_back();
    if (link.inertial && link.inertial->mass > 0.0) {
      const urdf::Inertial& in = *link.inertial;
      const Placement X_BI = X_BL * to_placement(in.origin);
      Matrix3d I;
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      if (Matrix3d repaired; options.repair_inertia && repair_inertia(I, repaired)) {
        I = repaired;
        model.repaired_inertia_links.push_back(link.name);
      }
      model.frame_inertia.back() =
          SpatialInertia::from_com(in.mass, X_BI.p, X_BI.R * I * X_BI.R.transpose());
      acc[body] += model.frame_inertia.back();
    }
    // children in file order
    std::vector<const urdf::Joint*> joints;
    for (const auto& j : link.child_joints) {
      joints.push_back(j.get());
    }
    std::sort(joints.begin(), joints.end(), [&](const urdf::Joint* a, const urdf::Joint* b) {
      return raw.at(a->name).order < raw.at(b->name).order;
    });
    for (const urdf::Joint* j : joints) {
      const urdf::LinkConstSharedPtr child = urdf.getLink(j->child_link_name);
      const Placement X_BJ = X_BL * to_placement(j->parent_to_joint_origin_transform);
      if (moves(*j)) {
        const int b = new_body(*j, body, X_BJ);
        add_link(*child, b, Placement{}, frame);
      } else {
        Placement X_JC;
        if (j->type != urdf::Joint::FIXED) {  // locked movable joint
          double q = 0.0;
          if (auto it = options.locked_positions.find(j->name);
              it != options.locked_positions.end()) {
            q = it->second;
          }
          const detail::JointCalc jc = detail::joint_calc(type_of(*j), axis_of(*j), q);
          X_JC = Placement{jc.R, jc.p};
          model.locked_joint_name.push_back(j->name);
          model.locked_joint_position.push_back(q);
        }
        add_link(*child, body, X_BJ * X_JC, frame);
      }
    }
  }

  static JointType type_of(const urdf::Joint& j) {
    return j.type == urdf::Joint::PRISMATIC ? JointType::kPrismatic : JointType::kRevolute;
  }
  Vector3d axis_of(const urdf::Joint& j) const {
    const Vector3d a(j.axis.x, j.axis.y, j.axis.z);
    if (!(a.norm() > 1e-12)) {
      err.fail("joint '" + j.name + "' has a zero axis");
    }
    return a.normalized();
  }

  int new_body(const urdf::Joint& j, int parent, const Placement& X_PJ) {
    const int b = static_cast<int>(model.parent.size());
    model.parent.push_back(parent);
    model.body_name.push_back(j.child_link_name);
    model.joint_R_PJ.push_back(X_PJ.R);
    model.joint_p_PJ.push_back(X_PJ.p);
    model.body_joint_type.push_back(type_of(j));
    model.body_joint_axis.push_back(axis_of(j));
    acc.emplace_back();
    joint_to_body[j.name] = b;
    return b;
  }
};

}  // namespace

Model load_urdf_string(const std::string& xml, const LoadOptions& options,
                       const std::string& source) {
  const Error err(source);
  if (xml.find_first_not_of(" \t\r\n") == std::string::npos) {
    err.fail("the file is empty");
  }
  const std::map<std::string, RawJoint> raw = check_structure(xml, err);
  urdf::ModelInterfaceSharedPtr urdf;
  try {
    urdf = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    err.fail(std::string("urdfdom: ") + e.what());
  }
  if (!urdf) {
    err.fail("urdfdom could not build the model (see its message above)");
  }
  for (const auto& [name, link] : urdf->links_) {
    check_inertial(*link, options.strict_inertia && !options.repair_inertia, err);
  }
  for (const auto& [name, joint] : urdf->joints_) {
    if (joint->type == urdf::Joint::FLOATING || joint->type == urdf::Joint::PLANAR ||
        joint->type == urdf::Joint::UNKNOWN) {
      err.fail("joint '" + name + "' has type '" + raw.at(name).type +
               "', which is not supported (revolute, continuous, prismatic, fixed)");
    }
  }

  Builder b{*urdf, raw, options, err, Model{}, {}, {}, {}};
  for (const std::string& j : options.joints) {
    const auto joint = urdf->getJoint(j);
    if (!joint) {
      throw std::invalid_argument("URDF '" + source + "': unknown joint '" + j + "'");
    }
    if (joint->type == urdf::Joint::FIXED) {
      throw std::invalid_argument("URDF '" + source + "': joint '" + j + "' is fixed");
    }
    if (!b.kept.insert(j).second) {
      throw std::invalid_argument("URDF '" + source + "': joint '" + j + "' is listed twice");
    }
  }
  for (const auto& [j, q] : options.locked_positions) {
    if (!urdf->getJoint(j)) {
      throw std::invalid_argument("URDF '" + source + "': unknown locked joint '" + j + "'");
    }
  }
  for (const auto& [j, a] : options.armature) {
    const auto joint = urdf->getJoint(j);
    if (!joint) {
      throw std::invalid_argument("URDF '" + source + "': armature for unknown joint '" + j + "'");
    }
    if (joint->type == urdf::Joint::FIXED) {
      throw std::invalid_argument("URDF '" + source + "': armature for joint '" + j +
                                  "', which is fixed");
    }
    if (!std::isfinite(a) || a < 0.0) {
      std::ostringstream value;
      value << a;
      throw std::invalid_argument("URDF '" + source + "': armature of joint '" + j + "' is " +
                                  value.str() + ", expected a finite value >= 0");
    }
  }

  const urdf::LinkConstSharedPtr root = urdf->getRoot();
  const bool massless_root = !root->inertial || root->inertial->mass <= 0.0;
  Model& m = b.model;
  m.name = urdf->getName();
  m.source = source;
  m.floating_base = !(options.fixed_base || (root->name == "world" && massless_root));
  m.base_nv = m.floating_base ? 6 : 0;
  m.base_nq = m.floating_base ? 7 : 0;
  // body 0: the root
  m.parent.push_back(-1);
  m.body_name.push_back(root->name);
  m.joint_R_PJ.push_back(Matrix3d::Identity());
  m.joint_p_PJ.push_back(Vector3d::Zero());
  m.body_joint_type.push_back(JointType::kRevolute);
  m.body_joint_axis.push_back(Vector3d::UnitZ());
  b.acc.emplace_back();
  b.add_link(*root, 0, Placement{}, -1);

  m.n_bodies = static_cast<int>(m.parent.size());
  m.n_joints = m.n_bodies - 1;
  m.nv = m.base_nv + m.n_joints;
  m.nq = m.base_nq + m.n_joints;
  // inertias: mass, CoM, inertia about the CoM, from the accumulated sums
  for (const SpatialInertia& I : b.acc) {
    const Vector3d c = I.m > 0.0 ? Vector3d(I.h / I.m) : Vector3d::Zero();
    m.body_mass.push_back(I.m);
    m.body_com.push_back(c);
    m.body_inertia_c.push_back(I.I -
                               I.m * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose()));
    m.body_inertia.push_back(I);
    m.total_mass += I.m;
  }
  // joint order: list order for a reduced model, else body order
  std::vector<int> order;  // bodies in ν order
  if (options.joints.empty()) {
    for (int i = 1; i < m.n_bodies; ++i) {
      order.push_back(i);
    }
  } else {
    for (const std::string& j : options.joints) {
      order.push_back(b.joint_to_body.at(j));
    }
  }
  m.body_subtree_size.assign(static_cast<std::size_t>(m.n_bodies), 1);
  for (int i = m.n_bodies - 1; i > 0; --i) {
    m.body_subtree_size[m.parent[i]] += m.body_subtree_size[i];
  }
  for (int k = 0; k < m.n_joints; ++k) {
    m.joint_order_is_body_order =
        m.joint_order_is_body_order && order[static_cast<std::size_t>(k)] == k + 1;
  }
  m.body_joint.assign(static_cast<std::size_t>(m.n_bodies), -1);
  m.body_q_index.assign(static_cast<std::size_t>(m.n_bodies), -1);
  m.body_v_index.assign(static_cast<std::size_t>(m.n_bodies), -1);
  for (int i = 0; i < m.n_bodies; ++i) {
    const Vector3d& a = m.body_joint_axis[i];
    int k = -1;
    double sign = 1.0;
    for (int c = 0; c < 3; ++c) {
      if (std::abs(std::abs(a[c]) - 1.0) == 0.0 && a.squaredNorm() == 1.0) {
        k = c;
        sign = a[c] > 0 ? 1.0 : -1.0;
      }
    }
    m.body_joint_axis_index.push_back(k);
    m.body_joint_axis_sign.push_back(sign);
    m.joint_R_PJ_identity.push_back(m.joint_R_PJ[i] == Matrix3d::Identity());
  }
  for (int k = 0; k < m.n_joints; ++k) {
    const int body = order[static_cast<std::size_t>(k)];
    std::string name;
    for (const auto& [jn, jb] : b.joint_to_body) {
      if (jb == body) {
        name = jn;
      }
    }
    const urdf::Joint& j = *urdf->getJoint(name);
    m.body_joint[body] = k;
    m.body_q_index[body] = m.base_nq + k;
    m.body_v_index[body] = m.base_nv + k;
    m.joint_name.push_back(name);
    m.joint_body.push_back(body);
    m.joint_q_index.push_back(m.base_nq + k);
    m.joint_v_index.push_back(m.base_nv + k);
    m.joint_type.push_back(Builder::type_of(j));
    const bool continuous = j.type == urdf::Joint::CONTINUOUS;
    m.joint_continuous.push_back(continuous);
    m.joint_lower.push_back(continuous || !j.limits ? -kInf : j.limits->lower);
    m.joint_upper.push_back(continuous || !j.limits ? kInf : j.limits->upper);
    m.joint_velocity_limit.push_back(j.limits && j.limits->velocity > 0 ? j.limits->velocity
                                                                        : kInf);
    m.joint_effort_limit.push_back(j.limits && j.limits->effort > 0 ? j.limits->effort : kInf);
    MimicInfo mimic;
    if (j.mimic) {
      mimic.joint = j.mimic->joint_name;
      mimic.multiplier = j.mimic->multiplier;
      mimic.offset = j.mimic->offset;
    }
    m.joint_mimic.push_back(mimic);
    const auto armature = options.armature.find(name);
    m.joint_armature.push_back(armature == options.armature.end() ? 0.0 : armature->second);
  }
  return m;
}

Model load_urdf_file(const std::string& path, const LoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw std::invalid_argument("URDF '" + path +
                                "': cannot open the file (missing or unreadable)");
  }
  std::ostringstream text;
  text << in.rdbuf();
  return load_urdf_string(text.str(), options, path);
}

}  // namespace wbi::model
