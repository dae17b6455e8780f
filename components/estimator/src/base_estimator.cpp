#include "wbi/estimator/base_estimator.hpp"

#include <stdexcept>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <wbi/model/algorithms.hpp>

#include "floating_base_model.hpp"

namespace wbi::estimator {

namespace {

using detail::set_base;

Eigen::Matrix4d inverse(const Eigen::Matrix4d& H) {
  Eigen::Matrix4d out = Eigen::Matrix4d::Identity();
  out.topLeftCorner<3, 3>() = H.topLeftCorner<3, 3>().transpose();
  out.topRightCorner<3, 1>() = -H.topLeftCorner<3, 3>().transpose() * H.topRightCorner<3, 1>();
  return out;
}

}  // namespace

FixedLinkBaseEstimator::FixedLinkBaseEstimator(const std::string& urdf,
                                               const std::vector<std::string>& joints,
                                               const std::string& link,
                                               const Eigen::Matrix4d& initial_world_H_base)
    : model_(detail::load_floating_base_model(urdf, joints)),
      data_(model_),
      q_model_(Eigen::VectorXd::Zero(model_.nq)),
      nu_(Eigen::VectorXd::Zero(model_.nv)) {
  state_.world_H_base = initial_world_H_base;
  set_fixed_link(link);
}

void FixedLinkBaseEstimator::set_fixed_link(const std::string& link) {
  if (!model_.has_frame(link)) {
    throw std::invalid_argument("unknown link '" + link + "' for the fixed-link base estimate of " +
                                model_.name);
  }
  link_ = model_.frame_id(link);
  started_ = false;  // the next update fixes the new link where the current estimate puts it
}

const std::string& FixedLinkBaseEstimator::fixed_link() const {
  return model_.frame_name[static_cast<std::size_t>(link_)];
}

Eigen::Matrix4d FixedLinkBaseEstimator::link_in_base(const Eigen::Ref<const Eigen::VectorXd>& q) {
  set_base(q_model_, Eigen::Matrix4d::Identity());
  q_model_.tail(model_.n_joints) = q;
  wbi::model::forward_kinematics(model_, data_, q_model_);
  return wbi::model::frame_pose(model_, data_, link_);
}

const BaseState& FixedLinkBaseEstimator::update(const Eigen::Ref<const Eigen::VectorXd>& q,
                                                const Eigen::Ref<const Eigen::VectorXd>& dq,
                                                const Eigen::Ref<const Eigen::VectorXd>& ddq) {
  if (q.size() != model_.n_joints || dq.size() != model_.n_joints ||
      ddq.size() != model_.n_joints) {
    throw std::invalid_argument("base estimate: joint vectors must have size " +
                                std::to_string(model_.n_joints));
  }
  const Eigen::Matrix4d base_H_link = link_in_base(q);
  if (!started_) {
    world_H_link_ = state_.world_H_base * base_H_link;
    started_ = true;
  }
  state_.world_H_base = world_H_link_ * inverse(base_H_link);

  // Velocity and acceleration from J ν = 0 and J ν̇ + J̇ ν = 0 at the estimated pose.
  set_base(q_model_, state_.world_H_base);
  nu_.head<6>().setZero();
  nu_.tail(model_.n_joints) = dq;
  wbi::model::forward_kinematics(model_, data_, q_model_);
  const Eigen::MatrixXd& J = wbi::model::frame_jacobian(model_, data_, link_);
  const Eigen::PartialPivLU<Eigen::Matrix<double, 6, 6>> J_base(J.leftCols<6>());
  const Eigen::Matrix<double, 6, 1> J_joints_dq = J.rightCols(model_.n_joints) * dq;
  state_.velocity = -J_base.solve(J_joints_dq);
  nu_.head<6>() = state_.velocity;
  wbi::model::forward_velocity_kinematics(model_, data_, q_model_, nu_);
  const Eigen::Matrix<double, 6, 1> J_joints_ddq = J.rightCols(model_.n_joints) * ddq;
  state_.acceleration =
      -J_base.solve(J_joints_ddq + wbi::model::frame_bias_acceleration(model_, data_, link_));
  return state_;
}

}  // namespace wbi::estimator
