#include "wbi/model_service/evaluator.hpp"

#include <chrono>
#include <cmath>
#include <exception>

#include <wbi/msg/eigen.hpp>

namespace wbi::model_service {

namespace {

// Copies m into result row-major.
template <class Derived>
void put(const Eigen::MatrixBase<Derived>& m, msg::OperationResult& result) {
  const auto rows = static_cast<std::size_t>(m.rows());
  const auto cols = static_cast<std::size_t>(m.cols());
  result.rows(static_cast<std::uint32_t>(rows));
  result.cols(static_cast<std::uint32_t>(cols));
  auto& data = result.data();
  data.resize(rows * cols);
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t j = 0; j < cols; ++j) {
      data[i * cols + j] = m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    }
  }
}

bool needs_frame(msg::ModelOperation operation) {
  return operation == msg::FRAME_POSE || operation == msg::JACOBIAN || operation == msg::DJNU;
}

const char* name_of(msg::ModelOperation operation) {
  switch (operation) {
    case msg::MASS_MATRIX:
      return "MASS_MATRIX";
    case msg::BIAS_FORCES:
      return "BIAS_FORCES";
    case msg::GRAVITY_FORCES:
      return "GRAVITY_FORCES";
    case msg::FRAME_POSE:
      return "FRAME_POSE";
    case msg::JACOBIAN:
      return "JACOBIAN";
    case msg::DJNU:
      return "DJNU";
    case msg::COM:
      return "COM";
    case msg::COM_JACOBIAN:
      return "COM_JACOBIAN";
    case msg::CENTROIDAL_MOMENTUM:
      return "CENTROIDAL_MOMENTUM";
    case msg::CENTROIDAL_MOMENTUM_MATRIX:
      return "CENTROIDAL_MOMENTUM_MATRIX";
    case msg::INVERSE_DYNAMICS:
      return "INVERSE_DYNAMICS";
    case msg::FORWARD_DYNAMICS:
      return "FORWARD_DYNAMICS";
  }
  return "unknown";
}

std::string size_error(const char* field, std::size_t got, int expected, const std::string& robot) {
  return std::string(field) + " has " + std::to_string(got) + " values, robot '" + robot +
         "' needs " + std::to_string(expected);
}

}  // namespace

Evaluator::Evaluator(const model::Model& model, std::string robot)
    : Evaluator(model::make_wbi_backend(model), nullptr, std::move(robot)) {}

Evaluator::Evaluator(model::ModelBackend& backend, std::string robot)
    : Evaluator(nullptr, &backend, std::move(robot)) {}

Evaluator::Evaluator(std::unique_ptr<model::ModelBackend> owned, model::ModelBackend* backend,
                     std::string robot)
    : owned_(std::move(owned)),
      backend_(owned_ ? *owned_ : *backend),
      model_(backend_.model()),
      robot_(std::move(robot)),
      q_(Eigen::VectorXd::Zero(model_.nq)),
      nu_(Eigen::VectorXd::Zero(model_.nv)),
      dnu_(Eigen::VectorXd::Zero(model_.nv)),
      tau_(Eigen::VectorXd::Zero(model_.nv)),
      gravity_(Eigen::Vector3d::Zero()) {
  wrenches_.reserve(16);
  frame_ids_.reserve(64);
  spare_.reserve(64);
  for (int i = 0; i < model_.n_frames(); ++i) {
    frames_.emplace(model_.frame_name[static_cast<std::size_t>(i)], i);
  }
}

bool Evaluator::load(const msg::ModelRequest& request, std::string& error) {
  const int n = model_.n_joints;
  const auto& state = request.state();
  if (request.robot() != robot_.c_str()) {
    error = "unknown robot '" + std::string(request.robot().c_str()) + "': this service serves '" +
            robot_ + "'";
    return false;
  }
  if (state.q().size() != static_cast<std::size_t>(n)) {
    error = size_error("state.q", state.q().size(), n, robot_);
    return false;
  }
  if (!state.dq().empty() && state.dq().size() != static_cast<std::size_t>(n)) {
    error = size_error("state.dq", state.dq().size(), n, robot_) + " (or none)";
    return false;
  }
  if (request.operations().size() > 64) {
    error = "at most 64 operations per request";
    return false;
  }
  // q and ν in the model's layout.
  const int bq = model_.base_nq;
  const int bv = model_.base_nv;
  if (model_.floating_base) {
    const auto& pose = state.base_pose();
    const auto& o = pose.orientation();
    const double norm = std::sqrt(o.w() * o.w() + o.x() * o.x() + o.y() * o.y() + o.z() * o.z());
    if (!(std::abs(norm - 1.0) < 1e-6)) {
      error = "state.base_pose.orientation must be a unit quaternion (w, x, y, z), norm is " +
              std::to_string(norm);
      return false;
    }
    msg::to_coordinates(pose, q_.head<7>());
    q_.segment<4>(3) /= norm;
    nu_.head<6>() = msg::to_eigen(state.base_velocity());
  }
  for (int k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    q_[bq + k] = state.q()[i];
    nu_[bv + k] = state.dq().empty() ? 0.0 : state.dq()[i];
  }
  gravity_ = msg::to_eigen(state.gravity());

  bool wants_id = false;
  bool wants_fd = false;
  frame_ids_.clear();
  for (const auto& operation : request.operations()) {
    wants_id = wants_id || operation.operation() == msg::INVERSE_DYNAMICS;
    wants_fd = wants_fd || operation.operation() == msg::FORWARD_DYNAMICS;
    int frame = -1;
    if (needs_frame(operation.operation())) {
      const auto it = frames_.find(std::string_view(operation.frame().c_str()));
      if (it == frames_.end()) {
        error = std::string(name_of(operation.operation())) + ": unknown frame '" +
                operation.frame().c_str() + "' in robot '" + robot_ + "'";
        return false;
      }
      frame = it->second;
    }
    frame_ids_.push_back(frame);
  }
  if (wants_id) {
    if (request.nu_dot().size() != static_cast<std::size_t>(model_.nv)) {
      error =
          "INVERSE_DYNAMICS: " + size_error("nu_dot", request.nu_dot().size(), model_.nv, robot_);
      return false;
    }
    for (int k = 0; k < model_.nv; ++k) {
      dnu_[k] = request.nu_dot()[static_cast<std::size_t>(k)];
    }
    wrenches_.clear();
    for (const auto& applied : request.wrenches()) {
      const auto it = frames_.find(std::string_view(applied.frame().c_str()));
      if (it == frames_.end()) {
        error = "INVERSE_DYNAMICS: unknown wrench frame '" + std::string(applied.frame().c_str()) +
                "' in robot '" + robot_ + "'";
        return false;
      }
      model::ExternalWrench external;
      external.frame = it->second;
      msg::to_eigen(applied.wrench(), external.wrench);
      wrenches_.push_back(external);
    }
  }
  if (wants_fd) {
    if (request.tau().size() != static_cast<std::size_t>(n)) {
      error = "FORWARD_DYNAMICS: " + size_error("tau", request.tau().size(), n, robot_);
      return false;
    }
    tau_.setZero();
    for (int k = 0; k < n; ++k) {
      tau_[bv + k] = request.tau()[static_cast<std::size_t>(k)];
    }
  }
  return true;
}

void Evaluator::compute(const msg::OperationRequest& operation, int frame,
                        msg::OperationResult& result) {
  result.operation(operation.operation());
  result.frame(operation.frame());
  switch (operation.operation()) {
    case msg::MASS_MATRIX:
      put(backend_.mass_matrix(q_), result);
      break;
    case msg::BIAS_FORCES:
      put(backend_.bias_forces(q_, nu_, gravity_), result);
      break;
    case msg::GRAVITY_FORCES:
      put(backend_.gravity_forces(q_, gravity_), result);
      break;
    case msg::FRAME_POSE:
      put(backend_.frame_pose(q_, frame), result);
      break;
    case msg::JACOBIAN:
      put(backend_.frame_jacobian(q_, frame), result);
      break;
    case msg::DJNU:
      put(backend_.frame_bias_acceleration(q_, nu_, frame), result);
      break;
    case msg::COM:
      put(backend_.center_of_mass(q_), result);
      break;
    case msg::COM_JACOBIAN:
      put(backend_.com_jacobian(q_), result);
      break;
    case msg::CENTROIDAL_MOMENTUM:
      put(backend_.centroidal_momentum(q_, nu_), result);
      break;
    case msg::CENTROIDAL_MOMENTUM_MATRIX:
      put(backend_.centroidal_momentum_matrix(q_), result);
      break;
    case msg::INVERSE_DYNAMICS:
      put(backend_.inverse_dynamics(q_, nu_, dnu_, gravity_, wrenches_), result);
      break;
    case msg::FORWARD_DYNAMICS:
      put(backend_.forward_dynamics(q_, nu_, tau_, gravity_), result);
      break;
  }
}

void Evaluator::resize_results(msg::ModelReply& reply, std::size_t count) {
  auto& results = reply.results();
  if (results.capacity() < 64) {
    results.reserve(64);
  }
  while (results.size() > count) {
    spare_.push_back(std::move(results.back()));
    results.pop_back();
  }
  while (results.size() < count) {
    if (spare_.empty()) {
      results.emplace_back();
    } else {
      results.push_back(std::move(spare_.back()));
      spare_.pop_back();
    }
  }
}

void Evaluator::evaluate(const msg::ModelRequest& request, msg::ModelReply& reply) {
  const auto start = std::chrono::steady_clock::now();
  std::string error;
  bool ok = load(request, error);
  if (ok) {
    auto& results = reply.results();
    const auto& operations = request.operations();
    resize_results(reply, operations.size());
    try {
      for (std::size_t i = 0; i < operations.size(); ++i) {
        compute(operations[i], frame_ids_[i], results[i]);
      }
    } catch (const std::exception& e) {
      ok = false;
      error = e.what();
    }
  }
  if (ok) {
    reply.error() = "";
  } else {
    resize_results(reply, 0);
    reply.error() = error;
  }
  reply.compute_ns(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start)
          .count());
}

msg::RobotDescription Evaluator::description(const std::string& urdf_path) const {
  msg::RobotDescription description;
  description.header().robot(robot_);
  description.floating_base(model_.floating_base);
  for (int k = 0; k < model_.n_joints; ++k) {
    const auto i = static_cast<std::size_t>(k);
    description.joint_names().push_back(model_.joint_name[i]);
    msg::JointLimits limits;
    limits.position_min(model_.joint_lower[i]);
    limits.position_max(model_.joint_upper[i]);
    limits.velocity_max(model_.joint_velocity_limit[i]);
    limits.effort_max(model_.joint_effort_limit[i]);
    description.joint_limits().push_back(limits);
  }
  description.urdf_path(urdf_path);
  return description;
}

}  // namespace wbi::model_service
