// DART → mixed representation (derivation in model_service/README.md, "DART backend").
//
// DART's root FreeJoint has velocity ν_D,B = (ω_b, v_b) = (Rᵀω, Rᵀṗ_B): angular
// first, body axes. With ν = (ṗ_B, ω_B, ṡ) (mixed) and P the permutation of the
// joints (wbi order → DART dof index):
//   ν_D = T ν,   T = diag(T_B, P),   T_B = [[0, Rᵀ], [Rᵀ, 0]]   (T orthogonal)
//   Ṫν = (0, −ω_b × v_b, 0)        (Ṙᵀ = −[ω_b]× Rᵀ)
//   M = Tᵀ M_D T,   τ = Tᵀ τ_D,   ν̇_D = T ν̇ + Ṫν
// so inverse dynamics is τ = Tᵀ ID_D(q, Tν, Tν̇ + Ṫν), h the same at ν̇ = 0,
// G = Tᵀ G_D, forward dynamics ν̇ = Tᵀ(FD_D(q, Tν, T τ) − Ṫν), J = swap · J_D T
// (DART's 6D rows are angular first), J̇ν = classic acceleration of the frame
// origin at ν̇_D = Ṫν.
#include "dart_backend.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/DegreeOfFreedom.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/Joint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/utils/urdf/DartLoader.hpp>

#include "checks.hpp"
#include "dart_urdf.hpp"
#include "wbi/model/configuration.hpp"

namespace wbi::model {

namespace {

using backend_detail::check_size;
namespace dd = dart::dynamics;

// Sends std::cerr to a stream while alive.
class CerrRedirect {
 public:
  explicit CerrRedirect(std::ostream& to) : previous_(std::cerr.rdbuf(to.rdbuf())) {}
  ~CerrRedirect() { std::cerr.rdbuf(previous_); }
  CerrRedirect(const CerrRedirect&) = delete;
  CerrRedirect& operator=(const CerrRedirect&) = delete;

 private:
  std::streambuf* previous_;
};

dd::SkeletonPtr load_skeleton(const std::string& urdf, const Model& model) {
  dart::utils::DartLoader::Options options;
  options.mDefaultRootJointType = model.floating_base
                                      ? dart::utils::DartLoader::RootJointType::FLOATING
                                      : dart::utils::DartLoader::RootJointType::FIXED;
  dart::utils::DartLoader loader(options);
  const std::string text = urdf_for_dart(urdf, model);
  // DART warns on std::cerr about every massless link; they are intended (wbi's
  // convention), so those lines are dropped and DART's other messages passed on.
  std::ostringstream messages;
  dd::SkeletonPtr skeleton;
  {
    static std::mutex loading;  // one redirect of std::cerr at a time
    const std::lock_guard<std::mutex> lock(loading);
    const CerrRedirect redirect(messages);
    skeleton = loader.parseSkeletonString(text, dart::common::Uri("file://" + urdf));
  }
  std::istringstream lines(messages.str());
  for (std::string line; std::getline(lines, line);) {
    if (line.find("negative or zero mass [0]") == std::string::npos) {
      std::fprintf(stderr, "%s\n", line.c_str());  // one call: the line stays whole
    }
  }
  if (!skeleton) {
    throw std::runtime_error(urdf + ": DART's URDF loader could not build a skeleton");
  }
  return skeleton;
}

class DartBackend final : public ModelBackend {
 public:
  DartBackend(Model model, const std::string& urdf)
      : model_(std::move(model)), skeleton_(load_skeleton(urdf, model_)) {
    const int n = model_.n_joints;
    nd_ = static_cast<int>(skeleton_->getNumDofs());
    if (nd_ != model_.base_nv + n) {
      throw std::runtime_error(urdf + ": DART built " + std::to_string(nd_) +
                               " degrees of freedom, wbi " + std::to_string(model_.nv));
    }
    if (model_.floating_base &&
        dynamic_cast<const dd::FreeJoint*>(skeleton_->getRootJoint()) == nullptr) {
      throw std::runtime_error(urdf + ": DART's root joint is not a free joint");
    }
    // Plain rigid-body dynamics: no joint springs, damping, friction or coupling.
    for (std::size_t j = 0; j < skeleton_->getNumJoints(); ++j) {
      skeleton_->getJoint(j)->setActuatorType(dd::Joint::FORCE);
    }
    for (int i = 0; i < nd_; ++i) {
      dd::DegreeOfFreedom* dof = skeleton_->getDof(static_cast<std::size_t>(i));
      dof->setDampingCoefficient(0.0);
      dof->setSpringStiffness(0.0);
      dof->setCoulombFriction(0.0);
      dofs_.push_back(dof);
    }
    for (int k = 0; k < n; ++k) {
      const std::string& name = model_.joint_name[static_cast<std::size_t>(k)];
      const dd::Joint* joint = skeleton_->getJoint(name);
      if (joint == nullptr || joint->getNumDofs() != 1) {
        throw std::runtime_error(urdf + ": joint '" + name + "' is not a 1-DoF joint in DART");
      }
      dof_of_joint_.push_back(static_cast<int>(joint->getDof(0)->getIndexInSkeleton()));
    }
    set_armature();
    for (int f = 0; f < model_.n_frames(); ++f) {
      const std::string& name = model_.frame_name[static_cast<std::size_t>(f)];
      dd::BodyNode* node = skeleton_->getBodyNode(name);
      // The only link DART does not make a body of: a fixed model's "world" root.
      if (node == nullptr &&
          !(model_.frame_body[static_cast<std::size_t>(f)] == 0 && !model_.floating_base)) {
        throw std::runtime_error(urdf + ": link '" + name + "' has no body in DART");
      }
      frame_node_.push_back(node);
    }
    for (std::size_t b = 0; b < skeleton_->getNumBodyNodes(); ++b) {
      bodies_.push_back(skeleton_->getBodyNode(b));
    }
    const auto nd = static_cast<Eigen::Index>(nd_);
    q_d_ = Eigen::VectorXd::Zero(nd);
    v_d_ = Eigen::VectorXd::Zero(nd);
    out_d_ = Eigen::VectorXd::Zero(nd);
    J_d_ = Eigen::MatrixXd::Zero(6, nd);
    MT_ = Eigen::MatrixXd::Zero(nd, model_.nv);
    M_ = Eigen::MatrixXd::Zero(model_.nv, model_.nv);
    vec_ = Eigen::VectorXd::Zero(model_.nv);
    J_ = Eigen::MatrixXd::Zero(6, model_.nv);
    J_com_ = Eigen::MatrixXd::Zero(3, model_.nv);
    Ag_d_ = Eigen::MatrixXd::Zero(6, nd);
    Ag_ = Eigen::MatrixXd::Zero(6, model_.nv);
    skeleton_->setGravity(gravity_);
  }

  std::string_view name() const override { return "dart"; }
  const Model& model() const override { return model_; }

  const Eigen::MatrixXd& mass_matrix(const ConstVectorRef& q) override {
    set_position(q);
    const Eigen::MatrixXd& M_d = skeleton_->getMassMatrix();
    mixed_columns(M_d, MT_);
    mixed_rows(MT_, M_);
    // Tᵀ M_D T is symmetric up to rounding in the base blocks; wbi's M is exactly so.
    for (Eigen::Index j = 0; j < M_.cols(); ++j) {
      for (Eigen::Index i = j + 1; i < M_.rows(); ++i) {
        M_(j, i) = M_(i, j);
      }
    }
    for (int k : armed_) {  // DART's M has no armature (see set_armature)
      const int v = model_.base_nv + k;
      M_(v, v) += model_.joint_armature[static_cast<std::size_t>(k)];
    }
    return M_;
  }

  const Eigen::VectorXd& bias_forces(const ConstVectorRef& q, const ConstVectorRef& nu,
                                     const Vector3d& gravity) override {
    return dynamics(q, nu, nullptr, gravity, {});
  }

  const Eigen::VectorXd& gravity_forces(const ConstVectorRef& q, const Vector3d& gravity) override {
    set_position(q);
    set_gravity(gravity);
    mixed_force(skeleton_->getGravityForces(), vec_);
    return vec_;
  }

  const Eigen::VectorXd& inverse_dynamics(const ConstVectorRef& q, const ConstVectorRef& nu,
                                          const ConstVectorRef& dnu, const Vector3d& gravity,
                                          std::span<const ExternalWrench> wrenches) override {
    check_size("dnu", dnu.size(), model_.nv);
    return dynamics(q, nu, &dnu, gravity, wrenches);
  }

  const Eigen::VectorXd& forward_dynamics(const ConstVectorRef& q, const ConstVectorRef& nu,
                                          const ConstVectorRef& tau, const Vector3d& gravity,
                                          std::span<const ExternalWrench> wrenches) override {
    check_size("tau", tau.size(), model_.nv);
    set_position(q);
    set_velocity(nu);
    set_gravity(gravity);
    dart_vector(tau, out_d_);  // τ_D = T⁻ᵀ τ = T τ
    for (int k : armed_) {     // cancels the force of the damping that carries the armature
      const int d = dof_of_joint_[static_cast<std::size_t>(k)];
      out_d_[d] += model_.joint_armature[static_cast<std::size_t>(k)] * v_d_[d];
    }
    for (int i = 0; i < nd_; ++i) {
      dofs_[static_cast<std::size_t>(i)]->setForce(out_d_[i]);
    }
    apply(wrenches);
    skeleton_->computeForwardDynamics();
    skeleton_->clearExternalForces();
    for (int i = 0; i < nd_; ++i) {
      out_d_[i] = dofs_[static_cast<std::size_t>(i)]->getAcceleration();
    }
    if (model_.floating_base) {
      out_d_.segment<3>(3) -= dT_nu_;
    }
    mixed_force(out_d_, vec_);  // ν̇ = Tᵀ(ν̇_D − Ṫν)
    return vec_;
  }

  const Eigen::Matrix4d& frame_pose(const ConstVectorRef& q, int frame) override {
    backend_detail::check_frame(model_, frame);
    set_position(q);
    const dd::BodyNode* node = frame_node_[static_cast<std::size_t>(frame)];
    pose_ = node == nullptr ? Eigen::Matrix4d::Identity() : node->getWorldTransform().matrix();
    return pose_;
  }

  const Eigen::MatrixXd& frame_jacobian(const ConstVectorRef& q, int frame) override {
    backend_detail::check_frame(model_, frame);
    set_position(q);
    J_d_.setZero();
    if (const dd::BodyNode* node = frame_node_[static_cast<std::size_t>(frame)]) {
      const auto& J_node = node->getWorldJacobian();  // angular first, world axes, body origin
      const auto& columns = node->getDependentGenCoordIndices();
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const auto col = static_cast<Eigen::Index>(columns[c]);
        J_d_.col(col).head<3>() = J_node.col(static_cast<Eigen::Index>(c)).tail<3>();
        J_d_.col(col).tail<3>() = J_node.col(static_cast<Eigen::Index>(c)).head<3>();
      }
    }
    mixed_columns(J_d_, J_);
    return J_;
  }

  const Vector6d& frame_bias_acceleration(const ConstVectorRef& q, const ConstVectorRef& nu,
                                          int frame) override {
    backend_detail::check_frame(model_, frame);
    set_position(q);
    set_velocity(nu);
    set_acceleration_bias();
    dJnu_.setZero();
    if (const dd::BodyNode* node = frame_node_[static_cast<std::size_t>(frame)]) {
      dJnu_.head<3>() = node->getLinearAcceleration();
      dJnu_.tail<3>() = node->getAngularAcceleration();
    }
    return dJnu_;
  }

  const Vector3d& center_of_mass(const ConstVectorRef& q) override {
    set_position(q);
    check_mass();
    com_ = skeleton_->getCOM();
    return com_;
  }

  const Eigen::MatrixXd& com_jacobian(const ConstVectorRef& q) override {
    centroidal_momentum_matrix(q);
    J_com_ = Ag_.topRows<3>() / skeleton_->getMass();
    return J_com_;
  }

  // h_G = Σ_i (m_i ċ_i, m_i (c_i − c) × ċ_i + R_i I_i R_iᵀ ω_i) over DART's bodies.
  const Vector6d& centroidal_momentum(const ConstVectorRef& q, const ConstVectorRef& nu) override {
    set_position(q);
    set_velocity(nu);
    check_mass();
    com_ = skeleton_->getCOM();
    hg_.setZero();
    for (const dd::BodyNode* body : bodies_) {
      const double m = body->getMass();
      const Eigen::Vector3d v_c = body->getLinearVelocity(body->getLocalCOM());
      const Eigen::Matrix3d& R = body->getWorldTransform().linear();
      hg_.head<3>() += m * v_c;
      hg_.tail<3>() +=
          m * (body->getCOM() - com_).cross(v_c) +
          R * (body->getInertia().getMoment() * (R.transpose() * body->getAngularVelocity()));
    }
    return hg_;
  }

  // A_G = Σ_i [m_i J_v,c_i ; m_i [c_i − c]× J_v,c_i + R_i I_i R_iᵀ J_ω,i] T, from each
  // body's world Jacobian (J_v,c_i = J_v,o_i − [R_i c_local]× J_ω,i).
  const Eigen::MatrixXd& centroidal_momentum_matrix(const ConstVectorRef& q) override {
    set_position(q);
    check_mass();
    com_ = skeleton_->getCOM();
    Ag_d_.setZero();
    for (const dd::BodyNode* body : bodies_) {
      const double m = body->getMass();
      const Eigen::Matrix3d& R = body->getWorldTransform().linear();
      const Eigen::Vector3d r = R * body->getLocalCOM();
      const Eigen::Vector3d c_rel = body->getCOM() - com_;
      const Eigen::Matrix3d I_world = R * body->getInertia().getMoment() * R.transpose();
      const auto& J_body = body->getWorldJacobian();
      const auto& columns = body->getDependentGenCoordIndices();
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const auto jc = static_cast<Eigen::Index>(c);
        const Eigen::Vector3d w = J_body.col(jc).head<3>();
        const Eigen::Vector3d v_c = J_body.col(jc).tail<3>() + w.cross(r);
        auto column = Ag_d_.col(static_cast<Eigen::Index>(columns[c]));
        column.head<3>() += m * v_c;
        column.tail<3>() += m * c_rel.cross(v_c) + I_world * w;
      }
    }
    mixed_columns(Ag_d_, Ag_);
    return Ag_;
  }

 private:
  // q → DART positions: the free joint's (rotation vector, translation), joints by name.
  void set_position(const ConstVectorRef& q) {
    check_configuration(model_, q);
    if (model_.floating_base) {
      const Eigen::Quaterniond quat(q[3], q[4], q[5], q[6]);
      R_ = quat.normalized().toRotationMatrix();
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.linear() = R_;
      pose.translation() = q.head<3>();
      q_d_.head<6>() = dd::FreeJoint::convertToPositions(pose);
    }
    for (int k = 0; k < model_.n_joints; ++k) {
      q_d_[dof_of_joint_[static_cast<std::size_t>(k)]] = q[model_.base_nq + k];
    }
    skeleton_->setPositions(q_d_);
  }

  // ν → ν_D = T ν; also Ṫν's non-zero part −ω_b × v_b.
  void set_velocity(const ConstVectorRef& nu) {
    check_size("nu", nu.size(), model_.nv);
    dart_vector(nu, v_d_);
    if (model_.floating_base) {
      dT_nu_ = -v_d_.head<3>().cross(v_d_.segment<3>(3));
    }
    skeleton_->setVelocities(v_d_);
  }

  // DART accelerations ν̇_D = T ν̇ + Ṫν (dnu null: ν̇ = 0).
  void set_acceleration(const ConstVectorRef* dnu) {
    if (dnu != nullptr) {
      dart_vector(*dnu, out_d_);
    } else {
      out_d_.setZero();
    }
    if (model_.floating_base) {
      out_d_.segment<3>(3) += dT_nu_;
    }
    // Per dof: Skeleton::setAccelerations allocates a temporary on every call.
    for (int i = 0; i < nd_; ++i) {
      dofs_[static_cast<std::size_t>(i)]->setAcceleration(out_d_[i]);
    }
  }
  void set_acceleration_bias() { set_acceleration(nullptr); }

  void set_gravity(const Vector3d& gravity) {
    if (gravity != gravity_) {
      gravity_ = gravity;
      skeleton_->setGravity(gravity_);
    }
  }

  void check_mass() const {
    if (!(skeleton_->getMass() > 0.0)) {
      throw std::invalid_argument("model '" + model_.name + "' has no mass: no centre of mass");
    }
  }

  // τ = Tᵀ ID_D(q, Tν, Tν̇ + Ṫν) with the wrenches; bias forces when dnu is null.
  const Eigen::VectorXd& dynamics(const ConstVectorRef& q, const ConstVectorRef& nu,
                                  const ConstVectorRef* dnu, const Vector3d& gravity,
                                  std::span<const ExternalWrench> wrenches) {
    set_position(q);
    set_velocity(nu);
    set_gravity(gravity);
    set_acceleration(dnu);
    apply(wrenches);
    skeleton_->computeInverseDynamics(!wrenches.empty(), false, false);
    skeleton_->clearExternalForces();
    for (int i = 0; i < nd_; ++i) {
      out_d_[i] = dofs_[static_cast<std::size_t>(i)]->getForce();
    }
    mixed_force(out_d_, vec_);
    if (dnu != nullptr) {
      for (int k : armed_) {  // τ_k += armature_k q̈_k (not in DART's inverse dynamics)
        const int v = model_.base_nv + k;
        vec_[v] += model_.joint_armature[static_cast<std::size_t>(k)] * (*dnu)[v];
      }
    }
    return vec_;
  }

  // DART 6.12 has no armature (rotor inertia). Its forward dynamics, however,
  // integrates joint damping d implicitly over the skeleton's time step h: the
  // joint's projected articulated inertia becomes Sᵀ I^A S + h d and its force
  // τ − d q̇ (GenericJoint::updateInvProjArtInertiaImplicitDynamic,
  // updateTotalForceDynamic). With h = 1 and d = armature, and d q̇ added back to
  // τ, that is exactly wbi's ABA with armature (aba.cpp). M and inverse dynamics
  // ignore damping: the armature is added to their results. Joints without
  // armature are left alone, so a model without it computes as before.
  void set_armature() {
    for (int k = 0; k < model_.n_joints; ++k) {
      const double a = model_.joint_armature[static_cast<std::size_t>(k)];
      if (a != 0.0) {
        armed_.push_back(k);
        dofs_[static_cast<std::size_t>(dof_of_joint_[static_cast<std::size_t>(k)])]
            ->setDampingCoefficient(a);
      }
    }
    if (!armed_.empty()) {
      skeleton_->setTimeStep(1.0);  // the backend never steps the skeleton in time
    }
  }

  // Wrench (force, moment about the frame origin, world axes) on the frame's body.
  void apply(std::span<const ExternalWrench> wrenches) {
    for (const ExternalWrench& w : wrenches) {
      backend_detail::check_frame(model_, w.frame);
      if (dd::BodyNode* node = frame_node_[static_cast<std::size_t>(w.frame)]) {
        node->addExtForce(w.wrench.head<3>(), Eigen::Vector3d::Zero(), false, true);
        node->addExtTorque(w.wrench.tail<3>(), false);
      }
    }
  }

  // x_D = T x (a velocity or acceleration, or a force: T⁻ᵀ = T).
  void dart_vector(const ConstVectorRef& x, Eigen::VectorXd& x_d) const {
    check_size("generalized vector", x.size(), model_.nv);
    if (model_.floating_base) {
      x_d.head<3>().noalias() = R_.transpose() * x.segment<3>(3);
      x_d.segment<3>(3).noalias() = R_.transpose() * x.head<3>();
    }
    for (int k = 0; k < model_.n_joints; ++k) {
      x_d[dof_of_joint_[static_cast<std::size_t>(k)]] = x[model_.base_nv + k];
    }
  }

  // x = Tᵀ x_D.
  void mixed_force(const Eigen::VectorXd& x_d, Eigen::VectorXd& x) const {
    if (model_.floating_base) {
      x.head<3>().noalias() = R_ * x_d.segment<3>(3);
      x.segment<3>(3).noalias() = R_ * x_d.head<3>();
    }
    for (int k = 0; k < model_.n_joints; ++k) {
      x[model_.base_nv + k] = x_d[dof_of_joint_[static_cast<std::size_t>(k)]];
    }
  }

  // X = X_D T (columns).
  void mixed_columns(const Eigen::MatrixXd& X_d, Eigen::MatrixXd& X) const {
    if (model_.floating_base) {
      X.leftCols<3>().noalias() = X_d.middleCols<3>(3) * R_.transpose();
      X.middleCols<3>(3).noalias() = X_d.leftCols<3>() * R_.transpose();
    }
    for (int k = 0; k < model_.n_joints; ++k) {
      X.col(model_.base_nv + k) = X_d.col(dof_of_joint_[static_cast<std::size_t>(k)]);
    }
  }

  // X = Tᵀ X_D (rows).
  void mixed_rows(const Eigen::MatrixXd& X_d, Eigen::MatrixXd& X) const {
    if (model_.floating_base) {
      X.topRows<3>().noalias() = R_ * X_d.middleRows<3>(3);
      X.middleRows<3>(3).noalias() = R_ * X_d.topRows<3>();
    }
    for (int k = 0; k < model_.n_joints; ++k) {
      X.row(model_.base_nv + k) = X_d.row(dof_of_joint_[static_cast<std::size_t>(k)]);
    }
  }

  const Model model_;
  dd::SkeletonPtr skeleton_;
  int nd_ = 0;                                       // DART dofs (= nv)
  std::vector<dd::DegreeOfFreedom*> dofs_;           // DART dof i
  std::vector<int> dof_of_joint_;                    // wbi joint k → DART dof index
  std::vector<int> armed_;                           // joints with a non-zero armature
  std::vector<dd::BodyNode*> frame_node_;            // wbi frame → DART body (null: the world)
  std::vector<const dd::BodyNode*> bodies_;          // every DART body
  Eigen::Matrix3d R_ = Eigen::Matrix3d::Identity();  // base orientation of the last q
  Eigen::Vector3d dT_nu_ = Eigen::Vector3d::Zero();  // linear base part of Ṫν (DART coordinates)
  Eigen::Vector3d gravity_ = Eigen::Vector3d(0.0, 0.0, -9.81);
  Eigen::VectorXd q_d_, v_d_, out_d_;
  Eigen::MatrixXd J_d_, MT_, M_, J_, J_com_, Ag_d_, Ag_;
  Eigen::VectorXd vec_;
  Eigen::Matrix4d pose_ = Eigen::Matrix4d::Identity();
  Vector6d dJnu_ = Vector6d::Zero();
  Vector6d hg_ = Vector6d::Zero();
  Vector3d com_ = Vector3d::Zero();
};

}  // namespace

std::unique_ptr<ModelBackend> make_dart_backend(const std::string& urdf,
                                                const LoadOptions& options) {
  return std::make_unique<DartBackend>(load_urdf_file(urdf, options), urdf);
}

}  // namespace wbi::model
