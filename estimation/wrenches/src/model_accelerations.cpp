#include "wbi/estimation/model_accelerations.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "wbi/model/aba.hpp"
#include "wbi/model/crba.hpp"
#include "wbi/model/jacobian.hpp"
#include "wbi/model/kinematics.hpp"

namespace wbi::estimation {

namespace {

Eigen::VectorXd checked(const Eigen::VectorXd& values, int joints, const char* what) {
  if (values.size() == 0) {
    return Eigen::VectorXd::Zero(joints);
  }
  if (values.size() != joints || !(values.array() >= 0.0).all()) {
    throw std::invalid_argument(std::string("model accelerations: ") + what + " needs " +
                                std::to_string(joints) + " values ≥ 0, got " +
                                std::to_string(values.size()));
  }
  return values;
}

}  // namespace

ModelAccelerations::ModelAccelerations(model::Model model, JointLosses losses,
                                       std::vector<int> contact_frames)
    : model_(std::move(model)),
      data_(model_),
      losses_(std::move(losses)),
      mass_llt_(model_.nv) {  // sized here: an assigned LLT copies its unset info (UBSan)
  const int n = model_.n_joints;
  losses_.damping = checked(losses_.damping, n, "damping");
  losses_.friction = checked(losses_.friction, n, "friction");
  if (!(losses_.stick_velocity > 0.0)) {
    throw std::invalid_argument("model accelerations: stick_velocity must be > 0 rad/s");
  }
  std::vector<int> bodies;
  for (const int frame : contact_frames) {
    if (frame < 0 || frame >= static_cast<int>(model_.frame_body.size())) {
      throw std::invalid_argument("model accelerations: no frame " + std::to_string(frame));
    }
    const int body = model_.frame_body[static_cast<std::size_t>(frame)];
    const auto at = std::find(bodies.begin(), bodies.end(), body);
    contact_of_.push_back(static_cast<int>(at - bodies.begin()));
    if (at == bodies.end()) {
      bodies.push_back(body);
      contact_frames_.push_back(frame);
    }
  }
  body_held_.assign(contact_frames_.size(), 0);
  stuck_.assign(static_cast<std::size_t>(n), 0);
  tau_net_.setZero(model_.nv);
  ddq_.setZero(model_.nv);
  delta_tau_.setZero(model_.nv);
  // At most every contact held and every joint stuck.
  const Eigen::Index rows = static_cast<Eigen::Index>(6 * contact_frames_.size()) + n;
  J_.setZero(rows, model_.nv);
  bias_.setZero(rows);
  MinvJt_.setZero(model_.nv, rows);
  A_.setZero(rows, rows);
  lambda_.setZero(rows);
  joint_row_.assign(static_cast<std::size_t>(n), -1);
}

const Eigen::VectorXd& ModelAccelerations::update(const Eigen::VectorXd& q,
                                                  const Eigen::VectorXd& nu,
                                                  const Eigen::VectorXd& tau,
                                                  std::span<const char> held) {
  if (held.size() != contact_of_.size()) {
    throw std::invalid_argument("model accelerations: " + std::to_string(held.size()) +
                                " contact states for " + std::to_string(contact_of_.size()) +
                                " contact frames");
  }
  const int n = model_.n_joints;
  const int b = model_.base_nv;
  // Losses: damping always; friction opposes a sliding joint, a slow one may be stuck.
  tau_net_.tail(n) = tau - losses_.damping.cwiseProduct(nu.tail(n));
  stuck_count_ = 0;
  for (int j = 0; j < n; ++j) {
    const double v = nu[b + j];
    const bool stuck = losses_.friction[j] > 0.0 && std::abs(v) < losses_.stick_velocity;
    stuck_[static_cast<std::size_t>(j)] = stuck ? 1 : 0;
    stuck_count_ += stuck ? 1 : 0;
    if (!stuck && v != 0.0) {
      tau_net_[b + j] -= std::copysign(losses_.friction[j], v);
    }
  }
  std::fill(body_held_.begin(), body_held_.end(), 0);
  for (std::size_t c = 0; c < held.size(); ++c) {
    if (held[c] != 0) {
      body_held_[static_cast<std::size_t>(contact_of_[c])] = 1;
    }
  }
  // The held contacts' rows, at the top of J_, before forward dynamics, which
  // overwrites the bias accelerations; the stuck joints' rows follow them.
  contact_rows_ = 0;
  if (std::find(body_held_.begin(), body_held_.end(), 1) != body_held_.end()) {
    model::forward_velocity_kinematics(model_, data_, q, nu);
    for (std::size_t c = 0; c < contact_frames_.size(); ++c) {
      if (body_held_[c] != 0) {
        J_.middleRows<6>(contact_rows_) = model::frame_jacobian(model_, data_, contact_frames_[c]);
        bias_.segment<6>(contact_rows_) =
            model::frame_bias_acceleration(model_, data_, contact_frames_[c]);
        contact_rows_ += 6;
      }
    }
  }
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  ddq_ = model::forward_dynamics(model_, data_, q, nu, tau_net_, gravity);
  if (contact_rows_ == 0 && stuck_count_ == 0) {
    return ddq_;
  }
  mass_llt_.compute(model::mass_matrix(model_, data_, q));
  solve_constraints();
  // A stuck joint whose hold needs more than its friction slides, pushed by that friction.
  bool released = false;
  for (int j = 0; j < n; ++j) {
    const int row = joint_row_[static_cast<std::size_t>(j)];
    if (row >= 0 && std::abs(lambda_[row]) > losses_.friction[j]) {
      stuck_[static_cast<std::size_t>(j)] = 0;
      --stuck_count_;
      delta_tau_[b + j] = std::copysign(losses_.friction[j], lambda_[row]);
      released = true;
    }
  }
  if (released) {
    mass_llt_.solveInPlace(delta_tau_);
    ddq_ += delta_tau_;
    delta_tau_.setZero();
    solve_constraints();
  }
  ddq_.noalias() += MinvJt_.leftCols(active_rows_) * lambda_.head(active_rows_);
  return ddq_;
}

void ModelAccelerations::solve_constraints() {
  // The stuck joints' rows after the held contacts' (update() wrote those).
  Eigen::Index m = contact_rows_;
  const int b = model_.base_nv;
  for (int j = 0; j < model_.n_joints; ++j) {
    auto& row = joint_row_[static_cast<std::size_t>(j)];
    row = -1;
    if (stuck_[static_cast<std::size_t>(j)] != 0) {
      J_.row(m).setZero();
      J_(m, b + j) = 1.0;
      bias_[m] = 0.0;
      row = static_cast<int>(m++);
    }
  }
  active_rows_ = m;
  if (m == 0) {
    return;
  }
  const auto J = J_.topRows(m);
  auto MinvJt = MinvJt_.leftCols(m);
  MinvJt = J.transpose();
  mass_llt_.solveInPlace(MinvJt);
  auto A = A_.topLeftCorner(m, m);
  A.noalias() = J * MinvJt;
  // Rows can be dependent (a leg's joints stuck while both its feet are held):
  // each diagonal 1e-12 larger, relative to itself (joint rows are M⁻¹'s
  // diagonal, up to 10⁴ apart), keeps A positive definite; q̈ moves by ~1e-9.
  A.diagonal() *= 1.0 + 1e-12;
  auto lambda = lambda_.head(m);
  lambda.noalias() = -J * ddq_;
  lambda -= bias_.head(m);
  Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> factor(A);  // in place: nothing allocated
  factor.solveInPlace(lambda);
}

}  // namespace wbi::estimation
