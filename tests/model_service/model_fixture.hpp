// Random model requests and their local evaluation with the model library, to
// check the model service's replies.
#pragma once

#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include <wbi/msg/model.h>
#include <wbi/model/algorithms.hpp>

namespace wbi::test {

// Every operation of the model service, frame operations twice (two frames in one request).
inline const std::vector<wbi::msg::ModelOperation>& every_model_operation() {
  static const std::vector<wbi::msg::ModelOperation> operations = {
      wbi::msg::MASS_MATRIX,
      wbi::msg::BIAS_FORCES,
      wbi::msg::GRAVITY_FORCES,
      wbi::msg::FRAME_POSE,
      wbi::msg::JACOBIAN,
      wbi::msg::DJNU,
      wbi::msg::COM,
      wbi::msg::COM_JACOBIAN,
      wbi::msg::CENTROIDAL_MOMENTUM,
      wbi::msg::CENTROIDAL_MOMENTUM_MATRIX,
      wbi::msg::JACOBIAN,
      wbi::msg::FRAME_POSE,
      wbi::msg::DJNU};
  return operations;
}

// A random state of model (unit quaternion, q, ν, gravity −9.81 z) and the
// given operations on random frames.
inline void random_model_request(const wbi::model::Model& model, const std::string& robot,
                                 std::mt19937& rng,
                                 const std::vector<wbi::msg::ModelOperation>& operations,
                                 wbi::msg::ModelRequest& request) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  request.robot(robot);
  auto& state = request.state();
  Eigen::Quaterniond quat(u(rng), u(rng), u(rng), u(rng));
  quat.normalize();
  state.base_pose().position().x(u(rng));
  state.base_pose().position().y(u(rng));
  state.base_pose().position().z(u(rng));
  state.base_pose().orientation().w(quat.w());
  state.base_pose().orientation().x(quat.x());
  state.base_pose().orientation().y(quat.y());
  state.base_pose().orientation().z(quat.z());
  for (auto& v : state.base_velocity()) {
    v = u(rng);
  }
  state.q().resize(static_cast<std::size_t>(model.n_joints));
  state.dq().resize(static_cast<std::size_t>(model.n_joints));
  for (std::size_t i = 0; i < state.q().size(); ++i) {
    state.q()[i] = u(rng);
    state.dq()[i] = u(rng);
  }
  state.gravity().x(0.0);
  state.gravity().y(0.0);
  state.gravity().z(-9.81);
  request.operations().resize(operations.size());
  std::uniform_int_distribution<int> frame(0, model.n_frames() - 1);
  for (std::size_t i = 0; i < operations.size(); ++i) {
    request.operations()[i].operation(operations[i]);
    request.operations()[i].frame(model.frame_name[static_cast<std::size_t>(frame(rng))]);
  }
}

// Empty when every result of reply matches the library's own evaluation of
// request (relative tolerance 1e-9), else what differs.
inline std::string model_mismatch(const wbi::model::Model& model, wbi::model::Data& data,
                                  const wbi::msg::ModelRequest& request,
                                  const wbi::msg::ModelReply& reply) {
  using namespace wbi::model;
  std::ostringstream why;
  if (reply.error().size() != 0) {
    return std::string("error reply: ") + reply.error().c_str();
  }
  if (reply.results().size() != request.operations().size()) {
    return "wrong number of results";
  }
  const auto& state = request.state();
  Eigen::VectorXd q(model.nq);
  Eigen::VectorXd nu(model.nv);
  const auto& o = state.base_pose().orientation();
  if (model.floating_base) {
    q.head<7>() << state.base_pose().position().x(), state.base_pose().position().y(),
        state.base_pose().position().z(), o.w(), o.x(), o.y(), o.z();
    for (int k = 0; k < 6; ++k) {
      nu[k] = state.base_velocity()[static_cast<std::size_t>(k)];
    }
  }
  for (int k = 0; k < model.n_joints; ++k) {
    q[model.base_nq + k] = state.q()[static_cast<std::size_t>(k)];
    nu[model.base_nv + k] = state.dq()[static_cast<std::size_t>(k)];
  }
  const Eigen::Vector3d g(state.gravity().x(), state.gravity().y(), state.gravity().z());
  for (std::size_t i = 0; i < reply.results().size(); ++i) {
    const auto& op = request.operations()[i];
    Eigen::MatrixXd expected;
    const int frame = model.has_frame(op.frame().c_str()) ? model.frame_id(op.frame().c_str()) : 0;
    switch (op.operation()) {
      case wbi::msg::MASS_MATRIX:
        expected = mass_matrix(model, data, q);
        break;
      case wbi::msg::BIAS_FORCES:
        expected = bias_forces(model, data, q, nu, g);
        break;
      case wbi::msg::GRAVITY_FORCES:
        expected = gravity_forces(model, data, q, g);
        break;
      case wbi::msg::FRAME_POSE:
        forward_kinematics(model, data, q);
        expected = frame_pose(model, data, frame);
        break;
      case wbi::msg::JACOBIAN:
        forward_kinematics(model, data, q);
        expected = frame_jacobian(model, data, frame);
        break;
      case wbi::msg::DJNU:
        forward_velocity_kinematics(model, data, q, nu);
        expected = frame_bias_acceleration(model, data, frame);
        break;
      case wbi::msg::COM:
        expected = center_of_mass(model, data, q);
        break;
      case wbi::msg::COM_JACOBIAN:
        expected = com_jacobian(model, data, q);
        break;
      case wbi::msg::CENTROIDAL_MOMENTUM:
        expected = centroidal_momentum(model, data, q, nu);
        break;
      case wbi::msg::CENTROIDAL_MOMENTUM_MATRIX:
        expected = centroidal_momentum_matrix(model, data, q);
        break;
      default:
        return "operation not checked here";
    }
    const auto& result = reply.results()[i];
    if (result.operation() != op.operation() || result.rows() != expected.rows() ||
        result.cols() != expected.cols() ||
        result.data().size() != static_cast<std::size_t>(expected.size())) {
      why << "result " << i << ": wrong operation or shape";
      return why.str();
    }
    for (Eigen::Index r = 0; r < expected.rows(); ++r) {
      for (Eigen::Index c = 0; c < expected.cols(); ++c) {
        const double got = result.data()[static_cast<std::size_t>(r * expected.cols() + c)];
        if (std::abs(got - expected(r, c)) > 1e-9 * (1.0 + std::abs(expected(r, c)))) {
          why << "result " << i << " (" << static_cast<int>(op.operation()) << ") at (" << r << ", "
              << c << "): " << got << " != " << expected(r, c);
          return why.str();
        }
      }
    }
  }
  return "";
}

}  // namespace wbi::test
