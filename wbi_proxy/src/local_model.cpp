#include "local_model.hpp"

#include <Eigen/Geometry>
#include <wbi/model/backend.hpp>

#include "base_pose.hpp"
#include "size_check.hpp"

namespace wbi::proxy {

namespace {

std::unique_ptr<wbi::model::ModelBackend> load(
    const std::string& urdf, const IdList& joints,
    const std::map<std::string, double>& locked_positions, const std::string& backend,
    const std::map<std::string, double>& armature) {
  wbi::model::LoadOptions options;
  options.joints = joints;
  options.locked_positions = locked_positions;
  options.armature = armature;
  try {
    return wbi::model::make_model_backend(backend, urdf, options);
  } catch (const std::exception& e) {
    throw Error(std::string("cannot build the model: ") + e.what());
  }
}

}  // namespace

LocalModel::LocalModel(const std::string& urdf, const IdList& joints,
                       const std::map<std::string, double>& locked_positions,
                       const std::string& backend, const std::map<std::string, double>& armature)
    : backend_(load(urdf, joints, locked_positions, backend, armature)),
      model_(backend_->model()),
      q_(Eigen::VectorXd::Zero(model_.nq)),
      nu_(Eigen::VectorXd::Zero(model_.nv)),
      dnu_(Eigen::VectorXd::Zero(model_.nv)),
      offset_(6 - model_.base_nv) {
  if (model_.floating_base) {
    q_[3] = 1.0;  // identity quaternion (w first)
  }
}

int LocalModel::frame_index(const std::string& frame) const {
  if (!model_.has_frame(frame)) {
    throw Error("unknown frame '" + frame + "' in model " + model_.name);
  }
  return model_.frame_id(frame);
}

JointLimits LocalModel::joint_limits(int joint) const {
  check_index("joint", joint, dofs());
  const auto k = static_cast<std::size_t>(joint);
  return {model_.joint_lower[k], model_.joint_upper[k], model_.joint_velocity_limit[k],
          model_.joint_effort_limit[k]};
}

void LocalModel::set_position(const ConstVectorRef& q, const Transform& world_H_base) {
  check_size("joint positions q", q.size(), dofs());
  if (model_.floating_base) {
    const Eigen::Quaterniond orientation = base_orientation(world_H_base);
    q_.head<3>() = world_H_base.topRightCorner<3, 1>();
    q_.segment<4>(3) << orientation.w(), orientation.x(), orientation.y(), orientation.z();
  }
  q_.tail(dofs()) = q;
}

void LocalModel::set_velocity(const ConstVectorRef& dq, const ConstVectorRef& base_velocity) {
  check_size("joint velocities dq", dq.size(), dofs());
  check_size("base velocity", base_velocity.size(), 6);
  if (model_.floating_base) {
    nu_.head<6>() = base_velocity;
  }
  nu_.tail(dofs()) = dq;
}

void LocalModel::expand_columns(const Eigen::MatrixXd& from, MatrixRef to, const char* what) const {
  check_size(what, to.cols(), 6 + dofs());
  check_size(what, to.rows(), from.rows());
  to.leftCols(offset_).setZero();
  to.rightCols(from.cols()) = from;
}

void LocalModel::expand_vector(const Eigen::VectorXd& from, VectorRef to, const char* what) const {
  check_size(what, to.size(), 6 + dofs());
  to.head(offset_).setZero();
  to.tail(from.size()) = from;
}

void LocalModel::frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                            Transform& out) {
  check_index("frame", frame, model_.n_frames());
  set_position(q, world_H_base);
  out = backend_->frame_pose(q_, frame);
}

void LocalModel::jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                          MatrixRef J) {
  check_index("frame", frame, model_.n_frames());
  set_position(q, world_H_base);
  expand_columns(backend_->frame_jacobian(q_, frame), J, "Jacobian");
}

void LocalModel::dj_nu(const ConstVectorRef& q, const Transform& world_H_base,
                       const ConstVectorRef& dq, const ConstVectorRef& base_velocity, int frame,
                       VectorRef out) {
  check_index("frame", frame, model_.n_frames());
  check_size("dJnu", out.size(), 6);
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  out = backend_->frame_bias_acceleration(q_, nu_, frame);
}

void LocalModel::mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) {
  set_position(q, world_H_base);
  check_size("mass matrix rows", M.rows(), 6 + dofs());
  const Eigen::MatrixXd& model_M = backend_->mass_matrix(q_);
  M.topRows(offset_).setZero();
  expand_columns(model_M, M.bottomRows(model_M.rows()), "mass matrix");
}

void LocalModel::bias_forces(const ConstVectorRef& q, const Transform& world_H_base,
                             const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                             const Eigen::Vector3d& gravity, VectorRef h) {
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  expand_vector(backend_->bias_forces(q_, nu_, gravity), h, "bias forces");
}

void LocalModel::gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                                const Eigen::Vector3d& gravity, VectorRef g) {
  set_position(q, world_H_base);
  expand_vector(backend_->gravity_forces(q_, gravity), g, "gravity forces");
}

void LocalModel::inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                                  const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                  const ConstVectorRef& ddq,
                                  const ConstVectorRef& base_acceleration,
                                  const Eigen::Vector3d& gravity, VectorRef tau) {
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  check_size("joint accelerations ddq", ddq.size(), dofs());
  check_size("base acceleration", base_acceleration.size(), 6);
  if (model_.floating_base) {
    dnu_.head<6>() = base_acceleration;
  }
  dnu_.tail(dofs()) = ddq;
  expand_vector(backend_->inverse_dynamics(q_, nu_, dnu_, gravity), tau, "generalized forces");
}

void LocalModel::centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                                     const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                     VectorRef out) {
  check_size("centroidal momentum", out.size(), 6);
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  out = backend_->centroidal_momentum(q_, nu_);
}

void LocalModel::centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                            MatrixRef A) {
  set_position(q, world_H_base);
  expand_columns(backend_->centroidal_momentum_matrix(q_), A, "centroidal momentum matrix");
}

void LocalModel::com(const ConstVectorRef& q, const Transform& world_H_base, Eigen::Vector3d& out) {
  set_position(q, world_H_base);
  out = backend_->center_of_mass(q_);
}

void LocalModel::com_jacobian(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef J) {
  set_position(q, world_H_base);
  expand_columns(backend_->com_jacobian(q_), J, "CoM Jacobian");
}

}  // namespace wbi::proxy
