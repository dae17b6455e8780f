// A deliberately naive, independent rigid-body implementation used as the
// reference in the tests. It shares no code with wbi::model: it reads the URDF
// with urdfdom itself, keeps every link as its own body (no lumping), chains
// 4×4 homogeneous transforms, builds each link's Jacobian from explicit
// geometry (a_k × (p − o_k) per revolute joint) and forms
//   M = Σ_L m_L J_cᵀ J_c + J_ωᵀ I_L J_ω
//   h = Σ_L J_cᵀ m_L (J̇_c ν − g) + J_ωᵀ (I_L J̇_ω ν + ω × I_L ω)
// Everything allocates; speed does not matter here.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace wbi::test {

class Reference {
 public:
  // joint_order: the model's joint names, which fixes the order of q and ν
  // (same layout as wbi::model: floating (p, quat w,x,y,z, s), ν = (ṗ, ω, q̇)).
  Reference(const std::string& urdf_path, bool floating,
            const std::vector<std::string>& joint_order);

  void set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& nu);

  int nv() const { return nv_; }
  bool has_link(const std::string& name) const;
  Eigen::Matrix4d link_pose(const std::string& name) const;
  Eigen::MatrixXd link_jacobian(const std::string& name) const;  // 6×nv at the link origin
  Eigen::Matrix<double, 6, 1> link_dJnu(const std::string& name) const;

  Eigen::MatrixXd mass_matrix() const;
  Eigen::VectorXd bias_forces(const Eigen::Vector3d& gravity) const;
  Eigen::VectorXd gravity_forces(const Eigen::Vector3d& gravity) const;
  double total_mass() const;
  Eigen::Vector3d com() const;
  Eigen::Matrix<double, 6, 1> centroidal_momentum() const;  // (L, K about the CoM)
  Eigen::MatrixXd centroidal_momentum_matrix() const;
  double kinetic_energy() const;
  double potential_energy(const Eigen::Vector3d& gravity) const;

 private:
  struct Link {
    std::string name;
    int parent = -1;         // parent link
    int joint_kind = 0;      // 0 fixed, 1 revolute, 2 prismatic
    int v_index = -1;        // column in ν of its joint, −1 if fixed
    Eigen::Matrix4d origin;  // parent link → joint frame
    Eigen::Vector3d axis;    // unit, joint frame
    double mass = 0.0;
    Eigen::Vector3d com;      // link frame
    Eigen::Matrix3d inertia;  // about the CoM, link frame
  };
  int index(const std::string& name) const;
  Eigen::Vector3d origin_of(int l) const {
    return T_[static_cast<std::size_t>(l)].topRightCorner<3, 1>();
  }
  Eigen::Matrix3d rot_of(int l) const {
    return T_[static_cast<std::size_t>(l)].topLeftCorner<3, 3>();
  }
  Eigen::Vector3d com_of(int l) const;
  // 3×nv Jacobian of a point fixed in link l (world coordinates), and of its rotation.
  Eigen::MatrixXd point_jacobian(int l, const Eigen::Vector3d& p) const;
  Eigen::MatrixXd rotation_jacobian(int l) const;
  // J̇ν of a point fixed in link l, and of the angular velocity.
  Eigen::Vector3d point_dJnu(int l, const Eigen::Vector3d& p) const;
  Eigen::Vector3d rotation_dJnu(int l) const;
  Eigen::Vector3d omega(int l) const { return rotation_jacobian(l) * nu_; }
  Eigen::Matrix3d world_inertia(int l) const;

  bool floating_;
  int nv_ = 0;
  std::vector<Link> links_;  // parents before children
  std::vector<Eigen::Matrix4d> T_;
  Eigen::VectorXd nu_;
};

}  // namespace wbi::test
