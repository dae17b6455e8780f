#include "wbi/model/configuration.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "checks.hpp"

namespace wbi::model {

Eigen::VectorXd neutral_configuration(const Model& model) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq);
  if (model.floating_base) {
    q[3] = 1.0;
  }
  return q;
}

Eigen::VectorXd make_configuration(const Model& model, const Eigen::Vector3d& p_WB,
                                   const Eigen::Quaterniond& quat_WB, const Eigen::VectorXd& s) {
  detail::check_size("make_configuration", "joint positions", s, model.n_joints);
  Eigen::VectorXd q = neutral_configuration(model);
  if (model.floating_base) {
    q.head<3>() = p_WB;
    q[3] = quat_WB.w();
    q[4] = quat_WB.x();
    q[5] = quat_WB.y();
    q[6] = quat_WB.z();
  } else if (!p_WB.isZero(0.0) ||
             !quat_WB.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs())) {
    throw std::invalid_argument("make_configuration: model '" + model.name +
                                "' has a fixed base; the base pose must be the identity");
  }
  q.tail(model.n_joints) = s;
  check_configuration(model, q);
  return q;
}

Eigen::VectorXd make_configuration(const Model& model, const Eigen::Matrix4d& world_H_base,
                                   const Eigen::VectorXd& s) {
  const Eigen::Matrix3d R = world_H_base.topLeftCorner<3, 3>();
  if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-9) || R.determinant() < 0.0 ||
      !world_H_base.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1))) {
    throw std::invalid_argument("make_configuration: world_H_base is not a rigid transform");
  }
  return make_configuration(model, world_H_base.topRightCorner<3, 1>(), Eigen::Quaterniond(R), s);
}

void check_configuration(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q) {
  if (q.size() != model.nq) {
    detail::throw_size("model", "q", model.nq, static_cast<long>(q.size()));
  }
  if (!q.allFinite()) {
    throw std::invalid_argument("q is not finite (NaN or inf)");
  }
  if (model.floating_base) {
    const double norm = q.segment<4>(3).norm();
    if (std::abs(norm - 1.0) > 1e-6) {
      throw std::invalid_argument("q: base quaternion (w,x,y,z) has norm " + std::to_string(norm) +
                                  ", expected a unit quaternion");
    }
  }
}

Eigen::VectorXd integrate(const Model& model, const Eigen::VectorXd& q, const Eigen::VectorXd& nu,
                          double dt) {
  check_configuration(model, q);
  detail::check_size("integrate", "nu", nu, model.nv);
  Eigen::VectorXd r = q;
  if (model.floating_base) {
    r.head<3>() += dt * nu.head<3>();
    const Eigen::Vector3d w = dt * nu.segment<3>(3);
    const double angle = w.norm();
    Eigen::Quaterniond dq = Eigen::Quaterniond::Identity();
    if (angle > 0.0) {
      dq = Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle));
    }
    const Eigen::Quaterniond q0(q[3], q[4], q[5], q[6]);
    const Eigen::Quaterniond q1 = (dq * q0).normalized();
    r[3] = q1.w();
    r[4] = q1.x();
    r[5] = q1.y();
    r[6] = q1.z();
  }
  r.tail(model.n_joints) += dt * nu.tail(model.n_joints);
  return r;
}

Eigen::VectorXd random_configuration(const Model& model, std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::VectorXd q = neutral_configuration(model);
  if (model.floating_base) {
    q.head<3>() = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    Eigen::Vector4d quat(unit(rng), unit(rng), unit(rng), unit(rng));
    while (quat.norm() < 1e-3) {
      quat = Eigen::Vector4d(unit(rng), unit(rng), unit(rng), unit(rng));
    }
    q.segment<4>(3) = quat.normalized();
  }
  for (int k = 0; k < model.n_joints; ++k) {
    double lo = model.joint_lower[static_cast<std::size_t>(k)];
    double hi = model.joint_upper[static_cast<std::size_t>(k)];
    const double span = model.joint_type[static_cast<std::size_t>(k)] == JointType::kRevolute
                            ? std::numbers::pi
                            : 1.0;
    if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo) {
      lo = -span;
      hi = span;
    }
    lo = std::max(lo, -span);  // huge limits (e.g. ±1e5 rad) sample [−π, π]
    hi = std::min(hi, span);
    if (hi < lo) {
      lo = hi = 0.5 * (lo + hi);
    }
    q[model.joint_q_index[static_cast<std::size_t>(k)]] = lo + (hi - lo) * 0.5 * (unit(rng) + 1.0);
  }
  return q;
}

}  // namespace wbi::model
