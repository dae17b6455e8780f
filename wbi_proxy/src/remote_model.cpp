#include "remote_model.hpp"

#include <wbi/dds/topics.hpp>
#include <wbi/model/urdf.hpp>

#include "base_pose.hpp"
#include "size_check.hpp"

namespace wbi::proxy {

namespace {

// Frame names of a URDF, or none when it cannot be read here.
IdList frames_of(const std::string& urdf, const msg::RobotDescription& description) {
  try {
    wbi::model::LoadOptions options;
    options.fixed_base = !description.floating_base();
    return wbi::model::load_urdf_file(urdf, options).frame_name;
  } catch (const std::exception&) {
    return {};
  }
}

// The replies of one model service: a second service of the same robot is dropped.
dds::ClientOptions one_server(std::function<void(const dds::ProducerEvent&)> on_event) {
  dds::ClientOptions options;
  options.producers = dds::ProducerPolicy::one(std::move(on_event));
  return options;
}

}  // namespace

RemoteModel::RemoteModel(dds::Participant& participant, const DdsInterfaceOptions& options)
    : robot_(options.robot),
      timeout_(options.model_timeout),
      urdf_(options.urdf),
      description_(participant, dds::topics::model_description(options.robot), dds::qos::kLatched,
                   nullptr, dds::ProducerPolicy::one(options.on_producer_event)),
      client_(participant, dds::topics::model_service(options.robot),
              one_server(options.on_producer_event)) {}

std::string RemoteModel::wait_ready(std::chrono::steady_clock::time_point deadline) {
  const auto left = [&] {
    return std::max(std::chrono::steady_clock::duration::zero(),
                    deadline - std::chrono::steady_clock::now());
  };
  std::string missing;
  if (!description_.wait_newer(description_rx_, 0, left())) {
    missing = "the model service's description on " + dds::topics::model_description(robot_);
  }
  if (!client_.wait_connected(left())) {
    missing += (missing.empty() ? "" : "; ") + std::string("the model service ") +
               client_.service() + " (model_service component)";
  }
  return missing;
}

void RemoteModel::bind(const IdList& controlled, const std::map<std::string, double>& locked) {
  const auto& description = description_rx_.sample;
  const auto& names = description.joint_names();
  const int n_service = static_cast<int>(names.size());
  floating_base_ = description.floating_base();
  base_nv_ = floating_base_ ? 6 : 0;
  service_nv_ = base_nv_ + n_service;

  controlled_ = controlled;
  service_joint_.clear();
  for (const auto& joint : controlled) {
    int found = -1;
    for (int s = 0; s < n_service; ++s) {
      if (names[static_cast<std::size_t>(s)] == joint) {
        found = s;
      }
    }
    if (found < 0) {
      throw Error("joint '" + joint + "' is not a joint of the model served by " +
                  client_.service());
    }
    service_joint_.push_back(found);
  }
  generalized_.assign(static_cast<std::size_t>(6 + dofs()), -1);
  for (int i = 0; i < base_nv_; ++i) {
    generalized_[static_cast<std::size_t>(i)] = i;
  }
  for (int k = 0; k < dofs(); ++k) {
    generalized_[static_cast<std::size_t>(6 + k)] =
        base_nv_ + service_joint_[static_cast<std::size_t>(k)];
  }

  // The request, filled once: the other joints stay where they are locked.
  request_.robot(robot_);
  auto& state = request_.state();
  state.q().assign(static_cast<std::size_t>(n_service), 0.0);
  state.dq().assign(static_cast<std::size_t>(n_service), 0.0);
  for (int s = 0; s < n_service; ++s) {
    const auto it = locked.find(names[static_cast<std::size_t>(s)].to_string());
    if (it != locked.end()) {
      state.q()[static_cast<std::size_t>(s)] = it->second;
    }
  }
  state.base_pose().orientation().w(1.0);
  request_.operations().resize(1);
  request_.nu_dot().assign(static_cast<std::size_t>(service_nv_), 0.0);

  const std::string urdf = !urdf_.empty() ? urdf_ : description.urdf_path().to_string();
  frames_ = urdf.empty() ? IdList{} : frames_of(urdf, description);
  frames_known_ = !frames_.empty();
}

int RemoteModel::frame_index(const std::string& frame) const {
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    if (frames_[i] == frame) {
      return static_cast<int>(i);
    }
  }
  if (frames_known_) {
    throw Error("unknown frame '" + frame + "' in the model served by " + client_.service());
  }
  frames_.push_back(frame);  // checked by the service at the first call
  return static_cast<int>(frames_.size()) - 1;
}

JointLimits RemoteModel::joint_limits(int joint) const {
  check_index("joint", joint, dofs());
  const auto& limits = description_rx_.sample.joint_limits().at(
      static_cast<std::size_t>(service_joint_[static_cast<std::size_t>(joint)]));
  return {limits.position_min(), limits.position_max(), limits.velocity_max(), limits.effort_max()};
}

void RemoteModel::set_position(const ConstVectorRef& q, const Transform& world_H_base) {
  check_size("joint positions q", q.size(), dofs());
  auto& state = request_.state();
  if (floating_base_) {
    check_rotation(world_H_base);
    msg::to_wire(world_H_base, state.base_pose());
  }
  for (int k = 0; k < dofs(); ++k) {
    state.q()[static_cast<std::size_t>(service_joint_[static_cast<std::size_t>(k)])] = q[k];
  }
}

void RemoteModel::set_velocity(const ConstVectorRef& dq, const ConstVectorRef& base_velocity) {
  check_size("joint velocities dq", dq.size(), dofs());
  check_size("base velocity", base_velocity.size(), 6);
  auto& state = request_.state();
  msg::to_wire(base_velocity.head<6>(), state.base_velocity());
  for (int k = 0; k < dofs(); ++k) {
    state.dq()[static_cast<std::size_t>(service_joint_[static_cast<std::size_t>(k)])] = dq[k];
  }
}

void RemoteModel::set_gravity(const Eigen::Vector3d& gravity) {
  msg::to_wire(gravity, request_.state().gravity());
}

const msg::OperationResult& RemoteModel::call(msg::ModelOperation operation, int frame,
                                              const char* what, std::uint32_t rows,
                                              std::uint32_t cols) {
  auto& op = request_.operations()[0];
  op.operation(operation);
  if (frame >= 0) {
    check_index("frame", frame, static_cast<int>(frames_.size()));
    op.frame() = frames_[static_cast<std::size_t>(frame)];
  }
  try {
    client_.call(request_, reply_, timeout_);
  } catch (const dds::TimeoutError& e) {
    throw TimeoutError(std::string("remote model ") + what + ": " + e.what());
  } catch (const dds::CallError& e) {
    if (e.status() == dds::CallStatus::not_connected) {
      // No server within the deadline (the model service is restarting, say):
      // late, as a missing reply is; a caller may try again at its next tick.
      throw TimeoutError(std::string("remote model ") + what + ": " + e.what());
    }
    throw Error(std::string("remote model ") + what + ": " + e.what());
  }
  if (reply_.error().size() != 0) {
    throw Error("remote model " + std::string(what) + ": the model service " + client_.service() +
                " answered: " + reply_.error().to_string());
  }
  if (reply_.results().size() != 1 || reply_.results()[0].rows() != rows ||
      reply_.results()[0].cols() != cols ||
      reply_.results()[0].data().size() != std::size_t{rows} * cols) {
    throw Error("remote model " + std::string(what) + ": the model service " + client_.service() +
                " sent a result of unexpected size (expected " + std::to_string(rows) + " x " +
                std::to_string(cols) + ")");
  }
  return reply_.results()[0];
}

void RemoteModel::map_columns(const msg::OperationResult& result, MatrixRef to) const {
  const auto cols = static_cast<std::size_t>(result.cols());
  for (Eigen::Index i = 0; i < to.cols(); ++i) {
    const int from = generalized_[static_cast<std::size_t>(i)];
    for (Eigen::Index r = 0; r < to.rows(); ++r) {
      to(r, i) =
          from < 0
              ? 0.0
              : result.data()[static_cast<std::size_t>(r) * cols + static_cast<std::size_t>(from)];
    }
  }
}

void RemoteModel::map_vector(const msg::OperationResult& result, VectorRef to) const {
  for (Eigen::Index i = 0; i < to.size(); ++i) {
    const int from = generalized_[static_cast<std::size_t>(i)];
    to[i] = from < 0 ? 0.0 : result.data()[static_cast<std::size_t>(from)];
  }
}

void RemoteModel::frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                             Transform& out) {
  set_position(q, world_H_base);
  const auto& result = call(msg::FRAME_POSE, frame, "frame_pose", 4, 4);
  out = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(result.data().data());
}

void RemoteModel::jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                           MatrixRef J) {
  check_size("Jacobian rows", J.rows(), 6);
  check_size("Jacobian columns", J.cols(), 6 + dofs());
  set_position(q, world_H_base);
  map_columns(call(msg::JACOBIAN, frame, "jacobian", 6, service_nv()), J);
}

void RemoteModel::dj_nu(const ConstVectorRef& q, const Transform& world_H_base,
                        const ConstVectorRef& dq, const ConstVectorRef& base_velocity, int frame,
                        VectorRef out) {
  check_size("dJnu", out.size(), 6);
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  const auto& result = call(msg::DJNU, frame, "dj_nu", 6, 1);
  out = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(result.data().data());
}

void RemoteModel::mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) {
  check_size("mass matrix rows", M.rows(), 6 + dofs());
  check_size("mass matrix columns", M.cols(), 6 + dofs());
  set_position(q, world_H_base);
  const auto& result = call(msg::MASS_MATRIX, -1, "mass_matrix", service_nv(), service_nv());
  const auto cols = static_cast<std::size_t>(result.cols());
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    const int row = generalized_[static_cast<std::size_t>(i)];
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      const int col = generalized_[static_cast<std::size_t>(j)];
      M(i, j) =
          row < 0 || col < 0
              ? 0.0
              : result.data()[static_cast<std::size_t>(row) * cols + static_cast<std::size_t>(col)];
    }
  }
}

void RemoteModel::bias_forces(const ConstVectorRef& q, const Transform& world_H_base,
                              const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                              const Eigen::Vector3d& gravity, VectorRef h) {
  check_size("bias forces", h.size(), 6 + dofs());
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  set_gravity(gravity);
  map_vector(call(msg::BIAS_FORCES, -1, "bias_forces", service_nv(), 1), h);
}

void RemoteModel::gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                                 const Eigen::Vector3d& gravity, VectorRef g) {
  check_size("gravity forces", g.size(), 6 + dofs());
  set_position(q, world_H_base);
  set_gravity(gravity);
  map_vector(call(msg::GRAVITY_FORCES, -1, "gravity_forces", service_nv(), 1), g);
}

void RemoteModel::inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                                   const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                   const ConstVectorRef& ddq,
                                   const ConstVectorRef& base_acceleration,
                                   const Eigen::Vector3d& gravity, VectorRef tau) {
  check_size("generalized forces", tau.size(), 6 + dofs());
  check_size("joint accelerations ddq", ddq.size(), dofs());
  check_size("base acceleration", base_acceleration.size(), 6);
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  set_gravity(gravity);
  auto& nu_dot = request_.nu_dot();
  for (int i = 0; i < base_nv_; ++i) {
    nu_dot[static_cast<std::size_t>(i)] = base_acceleration[i];
  }
  for (int k = 0; k < dofs(); ++k) {
    nu_dot[static_cast<std::size_t>(generalized_[static_cast<std::size_t>(6 + k)])] = ddq[k];
  }
  map_vector(call(msg::INVERSE_DYNAMICS, -1, "inverse_dynamics", service_nv(), 1), tau);
}

void RemoteModel::centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                                      const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                                      VectorRef out) {
  check_size("centroidal momentum", out.size(), 6);
  set_position(q, world_H_base);
  set_velocity(dq, base_velocity);
  const auto& result = call(msg::CENTROIDAL_MOMENTUM, -1, "centroidal_momentum", 6, 1);
  out = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(result.data().data());
}

void RemoteModel::centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                             MatrixRef A) {
  check_size("centroidal momentum matrix rows", A.rows(), 6);
  check_size("centroidal momentum matrix columns", A.cols(), 6 + dofs());
  set_position(q, world_H_base);
  map_columns(
      call(msg::CENTROIDAL_MOMENTUM_MATRIX, -1, "centroidal_momentum_matrix", 6, service_nv()), A);
}

void RemoteModel::com(const ConstVectorRef& q, const Transform& world_H_base,
                      Eigen::Vector3d& out) {
  set_position(q, world_H_base);
  const auto& result = call(msg::COM, -1, "com", 3, 1);
  out = Eigen::Map<const Eigen::Vector3d>(result.data().data());
}

void RemoteModel::com_jacobian(const ConstVectorRef& q, const Transform& world_H_base,
                               MatrixRef J) {
  check_size("CoM Jacobian rows", J.rows(), 3);
  check_size("CoM Jacobian columns", J.cols(), 6 + dofs());
  set_position(q, world_H_base);
  map_columns(call(msg::COM_JACOBIAN, -1, "com_jacobian", 3, service_nv()), J);
}

}  // namespace wbi::proxy
