#include "reference.hpp"

#include <urdf_parser/urdf_parser.h>
#include <Eigen/Geometry>
#include <stdexcept>

namespace wbi::test {

namespace {
Eigen::Matrix4d pose_matrix(const urdf::Pose& p) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() =
      Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
          .normalized()
          .toRotationMatrix();
  T.topRightCorner<3, 1>() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return T;
}
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}
}  // namespace

Reference::Reference(const std::string& urdf_path, bool floating,
                     const std::vector<std::string>& joint_order)
    : floating_(floating) {
  const auto urdf = urdf::parseURDFFile(urdf_path);
  if (!urdf) {
    throw std::runtime_error("reference: cannot parse " + urdf_path);
  }
  const int base = floating ? 6 : 0;
  nv_ = base + static_cast<int>(joint_order.size());
  // breadth-first from the root: parents before children
  std::vector<urdf::LinkConstSharedPtr> queue{urdf->getRoot()};
  for (std::size_t i = 0; i < queue.size(); ++i) {
    const auto& l = queue[i];
    Link link;
    link.name = l->name;
    link.origin.setIdentity();
    link.axis.setZero();
    link.com.setZero();
    link.inertia.setZero();
    if (l->parent_joint) {
      const auto& j = *l->parent_joint;
      link.parent = index(j.parent_link_name);
      link.origin = pose_matrix(j.parent_to_joint_origin_transform);
      link.axis = Eigen::Vector3d(j.axis.x, j.axis.y, j.axis.z).normalized();
      if (j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS) {
        link.joint_kind = 1;
      } else if (j.type == urdf::Joint::PRISMATIC) {
        link.joint_kind = 2;
      }
      if (link.joint_kind != 0) {
        for (std::size_t k = 0; k < joint_order.size(); ++k) {
          if (joint_order[k] == j.name) {
            link.v_index = base + static_cast<int>(k);
          }
        }
        if (link.v_index < 0) {
          throw std::runtime_error("reference: joint " + j.name + " not in the order given");
        }
      }
    }
    if (l->inertial) {
      const auto& in = *l->inertial;
      const Eigen::Matrix4d Ti = pose_matrix(in.origin);
      Eigen::Matrix3d I;
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      link.mass = in.mass;
      link.com = Ti.topRightCorner<3, 1>();
      link.inertia = Ti.topLeftCorner<3, 3>() * I * Ti.topLeftCorner<3, 3>().transpose();
    }
    links_.push_back(link);
    for (const auto& c : l->child_links) {
      queue.push_back(c);
    }
  }
  T_.assign(links_.size(), Eigen::Matrix4d::Identity());
}

int Reference::index(const std::string& name) const {
  for (std::size_t i = 0; i < links_.size(); ++i) {
    if (links_[i].name == name) {
      return static_cast<int>(i);
    }
  }
  throw std::runtime_error("reference: unknown link " + name);
}

bool Reference::has_link(const std::string& name) const {
  for (const auto& l : links_) {
    if (l.name == name) {
      return true;
    }
  }
  return false;
}

void Reference::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& nu) {
  nu_ = nu;
  const int qbase = floating_ ? 7 : 0;
  const int vbase = floating_ ? 6 : 0;
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const Link& l = links_[i];
    if (l.parent < 0) {
      T_[i].setIdentity();
      if (floating_) {
        T_[i].topLeftCorner<3, 3>() =
            Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized().toRotationMatrix();
        T_[i].topRightCorner<3, 1>() = q.head<3>();
      }
      continue;
    }
    Eigen::Matrix4d motion = Eigen::Matrix4d::Identity();
    if (l.joint_kind != 0) {
      const double qi = q[qbase + (l.v_index - vbase)];
      if (l.joint_kind == 1) {
        motion.topLeftCorner<3, 3>() = Eigen::AngleAxisd(qi, l.axis).toRotationMatrix();
      } else {
        motion.topRightCorner<3, 1>() = qi * l.axis;
      }
    }
    T_[i] = T_[static_cast<std::size_t>(l.parent)] * l.origin * motion;
  }
}

Eigen::Vector3d Reference::com_of(int l) const {
  return origin_of(l) + rot_of(l) * links_[static_cast<std::size_t>(l)].com;
}

Eigen::Matrix3d Reference::world_inertia(int l) const {
  return rot_of(l) * links_[static_cast<std::size_t>(l)].inertia * rot_of(l).transpose();
}

Eigen::MatrixXd Reference::point_jacobian(int l, const Eigen::Vector3d& p) const {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, nv_);
  if (floating_) {
    J.leftCols<3>().setIdentity();
    J.middleCols<3>(3) = -cross_matrix(p - origin_of(0));
  }
  for (int k = l; links_[static_cast<std::size_t>(k)].parent >= 0;
       k = links_[static_cast<std::size_t>(k)].parent) {
    const Link& lk = links_[static_cast<std::size_t>(k)];
    if (lk.joint_kind == 0) {
      continue;
    }
    // the joint frame of link k is its own frame: axis R_k a, origin o_k
    const Eigen::Vector3d a = rot_of(k) * lk.axis;
    // fixed-size 3×1 blocks here and below, not J.col(): g++ 12 -Warray-bounds with AVX
    // (model_service/src/joint.hpp)
    J.block<3, 1>(0, lk.v_index) =
        lk.joint_kind == 1 ? Eigen::Vector3d(a.cross(p - origin_of(k))) : a;
  }
  return J;
}

Eigen::MatrixXd Reference::rotation_jacobian(int l) const {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, nv_);
  if (floating_) {
    J.middleCols<3>(3).setIdentity();
  }
  for (int k = l; links_[static_cast<std::size_t>(k)].parent >= 0;
       k = links_[static_cast<std::size_t>(k)].parent) {
    const Link& lk = links_[static_cast<std::size_t>(k)];
    if (lk.joint_kind == 1) {
      J.block<3, 1>(0, lk.v_index) = rot_of(k) * lk.axis;
    }
  }
  return J;
}

Eigen::Vector3d Reference::point_dJnu(int l, const Eigen::Vector3d& p) const {
  const Eigen::Vector3d pdot = point_jacobian(l, p) * nu_;
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  if (floating_) {
    // d/dt(ω_B × (p − p_B)) at constant ω_B
    r += nu_.segment<3>(3).cross(pdot - nu_.head<3>());
  }
  for (int k = l; links_[static_cast<std::size_t>(k)].parent >= 0;
       k = links_[static_cast<std::size_t>(k)].parent) {
    const Link& lk = links_[static_cast<std::size_t>(k)];
    if (lk.joint_kind == 0) {
      continue;
    }
    const int parent = lk.parent;
    const Eigen::Vector3d a = rot_of(k) * lk.axis;
    const Eigen::Vector3d adot = omega(parent).cross(a);  // the axis is fixed in the parent link
    const double qd = nu_[lk.v_index];
    if (lk.joint_kind == 1) {
      const Eigen::Vector3d o = origin_of(k);
      const Eigen::Vector3d odot = point_jacobian(parent, o) * nu_;
      r += (adot.cross(p - o) + a.cross(pdot - odot)) * qd;
    } else {
      r += adot * qd;
    }
  }
  return r;
}

Eigen::Vector3d Reference::rotation_dJnu(int l) const {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int k = l; links_[static_cast<std::size_t>(k)].parent >= 0;
       k = links_[static_cast<std::size_t>(k)].parent) {
    const Link& lk = links_[static_cast<std::size_t>(k)];
    if (lk.joint_kind == 1) {
      r += omega(lk.parent).cross(rot_of(k) * lk.axis) * nu_[lk.v_index];
    }
  }
  return r;
}

Eigen::Matrix4d Reference::link_pose(const std::string& name) const {
  return T_[static_cast<std::size_t>(index(name))];
}

Eigen::MatrixXd Reference::link_jacobian(const std::string& name) const {
  const int l = index(name);
  Eigen::MatrixXd J(6, nv_);
  J.topRows<3>() = point_jacobian(l, origin_of(l));
  J.bottomRows<3>() = rotation_jacobian(l);
  return J;
}

Eigen::Matrix<double, 6, 1> Reference::link_dJnu(const std::string& name) const {
  const int l = index(name);
  Eigen::Matrix<double, 6, 1> r;
  r.head<3>() = point_dJnu(l, origin_of(l));
  r.tail<3>() = rotation_dJnu(l);
  return r;
}

Eigen::MatrixXd Reference::mass_matrix() const {
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(nv_, nv_);
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const int l = static_cast<int>(i);
    const Eigen::MatrixXd Jc = point_jacobian(l, com_of(l));
    const Eigen::MatrixXd Jw = rotation_jacobian(l);
    M += links_[i].mass * Jc.transpose() * Jc + Jw.transpose() * world_inertia(l) * Jw;
  }
  return M;
}

Eigen::VectorXd Reference::bias_forces(const Eigen::Vector3d& gravity) const {
  Eigen::VectorXd h = Eigen::VectorXd::Zero(nv_);
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const int l = static_cast<int>(i);
    const double m = links_[i].mass;
    const Eigen::Vector3d c = com_of(l);
    const Eigen::Matrix3d I = world_inertia(l);
    const Eigen::Vector3d w = omega(l);
    const Eigen::Vector3d force = m * (point_dJnu(l, c) - gravity);
    const Eigen::Vector3d torque = I * rotation_dJnu(l) + w.cross(I * w);
    h += point_jacobian(l, c).transpose() * force + rotation_jacobian(l).transpose() * torque;
  }
  return h;
}

Eigen::VectorXd Reference::gravity_forces(const Eigen::Vector3d& gravity) const {
  Eigen::VectorXd g = Eigen::VectorXd::Zero(nv_);
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const int l = static_cast<int>(i);
    g -= point_jacobian(l, com_of(l)).transpose() * (links_[i].mass * gravity);
  }
  return g;
}

double Reference::total_mass() const {
  double m = 0.0;
  for (const auto& l : links_) {
    m += l.mass;
  }
  return m;
}

Eigen::Vector3d Reference::com() const {
  Eigen::Vector3d mc = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < links_.size(); ++i) {
    mc += links_[i].mass * com_of(static_cast<int>(i));
  }
  return mc / total_mass();
}

Eigen::MatrixXd Reference::centroidal_momentum_matrix() const {
  const Eigen::Vector3d c = com();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, nv_);
  for (std::size_t i = 0; i < links_.size(); ++i) {
    const int l = static_cast<int>(i);
    const Eigen::Vector3d ci = com_of(l);
    const Eigen::MatrixXd Jl = links_[i].mass * point_jacobian(l, ci);
    A.topRows<3>() += Jl;
    A.bottomRows<3>() += cross_matrix(ci - c) * Jl + world_inertia(l) * rotation_jacobian(l);
  }
  return A;
}

Eigen::Matrix<double, 6, 1> Reference::centroidal_momentum() const {
  return centroidal_momentum_matrix() * nu_;
}

double Reference::kinetic_energy() const { return 0.5 * nu_.dot(mass_matrix() * nu_); }

double Reference::potential_energy(const Eigen::Vector3d& gravity) const {
  return -total_mass() * gravity.dot(com());
}

}  // namespace wbi::test
