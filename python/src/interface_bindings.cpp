// wbi.DdsInterface: the whole-body interface over DDS (make_dds_interface) for
// Python; its vocabulary (ControlMode, …, Stamp, the errors) is bound by
// vocabulary_bindings.cpp. Same semantics as the C++ interface (wbi_proxy/README.md): joint
// vectors follow the add_joints order; model quantities have 6 + dofs entries
// (mixed base velocity, base first) with the base pose as an explicit 4x4
// argument. Reads return (values, Stamp); every read and model call accepts
// `out=` to fill a preallocated array instead of creating one. Blocking calls
// release the GIL.
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <wbi/dds/join_options.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/deploy/placement.hpp>

#include "bindings.hpp"
#include "numpy_out.hpp"

namespace wbi::python {

namespace {

using ConstVector = Eigen::Ref<const Eigen::VectorXd>;
const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

std::chrono::milliseconds milliseconds(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000.0));
}

DdsInterfaceOptions::ModelSource model_source_from(const std::string& name) {
  if (name == "local") {
    return DdsInterfaceOptions::ModelSource::local;
  }
  if (name == "remote") {
    return DdsInterfaceOptions::ModelSource::remote;
  }
  throw py::value_error("model is '" + name + "'; expected local or remote");
}

// Runs a call that may wait (blocking reads, DDS) with the GIL released, so
// that other Python threads run meanwhile.
template <typename Call>
auto without_gil(Call&& call) {
  py::gil_scoped_release release;
  return call();
}

// The interface and the sizes its reads need.
class PythonInterface {
 public:
  explicit PythonInterface(const DdsInterfaceOptions& options)
      : robot_(make_dds_interface(options)) {}

  WholeBodyInterface& robot() { return *robot_; }
  Eigen::Index nv() const { return 6 + robot_->dofs(); }

  Eigen::Index sensor_count(SensorKind kind) const {
    return static_cast<Eigen::Index>(robot_->sensor_list(kind).size());
  }
  Eigen::Index estimate_count(EstimateKind kind) const {
    // The sensor list only when asked for: before init() it throws, and a
    // size check of the other kinds must still name the size.
    const auto sensors = kind == EstimateKind::force_torque
                             ? static_cast<int>(sensor_count(SensorKind::force_torque))
                             : 0;
    const auto links = kind == EstimateKind::external_wrench
                           ? static_cast<int>(robot_->external_wrench_links().size())
                           : 0;
    return wbi::estimate_count(kind, robot_->dofs(), sensors, links);
  }

 private:
  std::unique_ptr<WholeBodyInterface> robot_;
};

}  // namespace

// Joins as every wbi tool does (dds/README.md, "Joining a deployment"):
// defaults < the deploy file < WBI_* environment < these keyword arguments.
dds::ParticipantOptions join_from_keywords(
    const std::string& participant_name, const std::optional<std::string>& deploy,
    std::optional<int> domain_id, const std::optional<std::string>& discovery,
    const std::optional<std::vector<std::string>>& peers,
    const std::optional<std::vector<std::string>>& interfaces,
    const std::optional<std::string>& discovery_server, const std::optional<std::string>& qos_file,
    const std::optional<std::string>& security, const std::optional<std::string>& identity) {
  dds::ParticipantOptions join;
  join.name = participant_name;
  try {
    if (deploy) {
      deploy::read_join_options(*deploy, identity.value_or(""), join);
    }
    dds::apply_environment(join);
    dds::JoinOverrides keywords;
    keywords.domain_id = domain_id;
    if (discovery) {
      keywords.discovery = dds::discovery_named(*discovery, "discovery");
    }
    keywords.peers = peers;
    keywords.interfaces = interfaces;
    keywords.discovery_server = discovery_server;
    keywords.qos_file = qos_file;
    keywords.security_directory = security;
    keywords.identity = identity;
    dds::apply(keywords, join);
  } catch (const std::exception& error) {
    throw py::value_error(error.what());
  }
  if (join.security.enabled() && join.security.identity.empty()) {
    throw py::value_error("the deployment is secured (" + join.security.directory +
                          "): give identity=NAME, an identity of that directory");
  }
  return join;
}

namespace {

PythonInterface make_interface(
    const std::string& robot, const std::string& urdf,
    const std::optional<std::vector<std::string>>& joints, const std::string& controller,
    const std::string& model, const std::map<std::string, double>& locked_positions,
    double max_age_s, double blocking_read_timeout_s, double model_timeout_s,
    std::optional<int> domain_id, const std::optional<std::string>& discovery,
    const std::string& participant_name, const std::optional<std::string>& qos_file,
    const std::map<std::string, double>& armature, const std::optional<std::string>& deploy,
    const std::optional<std::vector<std::string>>& peers,
    const std::optional<std::vector<std::string>>& interfaces,
    const std::optional<std::string>& discovery_server, const std::optional<std::string>& security,
    const std::optional<std::string>& identity, const std::string& claim) {
  DdsInterfaceOptions options;
  options.robot = robot;
  options.urdf = urdf;
  options.controller = controller;
  const auto claim_mode = claim_from_text(claim);
  if (!claim_mode) {
    throw py::value_error("claim is '" + claim + "': expected 'claim', 'force' or 'none'");
  }
  options.claim = *claim_mode;
  options.model_source = model_source_from(model);
  options.locked_positions = locked_positions;
  options.armature = armature;
  options.max_age_s = max_age_s;
  options.blocking_read_timeout = milliseconds(blocking_read_timeout_s);
  options.model_timeout = milliseconds(model_timeout_s);
  options.participant =
      join_from_keywords(participant_name, deploy, domain_id, discovery, peers, interfaces,
                         discovery_server, qos_file, security, identity);
  PythonInterface result(options);
  if (joints) {
    result.robot().add_joints(*joints);
  }
  return result;
}

void bind_reads(py::class_<PythonInterface>& interface) {
  using py::arg;
  const auto none = py::none();
  interface
      .def(
          "read_sensors",
          [](PythonInterface& self, SensorKind kind, ReadMode mode, const py::object& out) {
            Array values =
                vector_out(out, self.sensor_count(kind) * sensor_width(kind), "read_sensors");
            auto map = as_vector(values);
            const Stamp stamp = without_gil([&] { return self.robot().read_sensors(kind, map, mode); });
            return py::make_tuple(values, stamp);
          },
          arg("kind"), arg("mode") = ReadMode::latest, arg("out") = none,
          "(values, Stamp): every sensor of a kind, stacked")
      .def(
          "read_sensor",
          [](PythonInterface& self, SensorKind kind, int index, ReadMode mode,
             const py::object& out) {
            Array values = vector_out(out, sensor_width(kind), "read_sensor");
            auto map = as_vector(values);
            const Stamp stamp = without_gil([&] { return self.robot().read_sensor(kind, index, map, mode); });
            return py::make_tuple(values, stamp);
          },
          arg("kind"), arg("index"), arg("mode") = ReadMode::latest, arg("out") = none)
      .def(
          "read_estimates",
          [](PythonInterface& self, EstimateKind kind, ReadMode mode, const py::object& out) {
            Array values =
                vector_out(out, self.estimate_count(kind) * estimate_width(kind), "read_estimates");
            auto map = as_vector(values);
            const Stamp stamp = without_gil([&] { return self.robot().read_estimates(kind, map, mode); });
            return py::make_tuple(values, stamp);
          },
          arg("kind"), arg("mode") = ReadMode::latest, arg("out") = none,
          "(values, Stamp): every estimate of a kind, stacked")
      .def(
          "read_estimate",
          [](PythonInterface& self, EstimateKind kind, int index, ReadMode mode,
             const py::object& out) {
            Array values = vector_out(out, estimate_width(kind), "read_estimate");
            auto map = as_vector(values);
            const Stamp stamp = without_gil([&] { return self.robot().read_estimate(kind, index, map, mode); });
            return py::make_tuple(values, stamp);
          },
          arg("kind"), arg("index"), arg("mode") = ReadMode::latest, arg("out") = none)
      .def(
          "robot_state",
          [](PythonInterface& self) { return RobotState(self.robot().dofs()); },
          "a RobotState sized for the controlled joints, to pass to read_robot_state")
      .def(
          "read_robot_state",
          [](PythonInterface& self, RobotState& state, ReadMode mode) {
            // Sized once by robot_state(): a resize here would move the data under the views.
            if (state.q.size() != self.robot().dofs()) {
              throw py::value_error("read_robot_state: the RobotState has " +
                                    std::to_string(state.q.size()) + " joints, the interface " +
                                    std::to_string(self.robot().dofs()) +
                                    "; make it with robot_state()");
            }
            return without_gil([&] { return self.robot().state().read_robot_state(state, mode); });
          },
          arg("state"), arg("mode") = ReadMode::latest,
          "Stamp: fills `state` in place from one estimate (its arrays are views)")
      .def(
          "read_base_pose",
          [](PythonInterface& self, ReadMode mode) {
            Transform world_H_base;
            const Stamp stamp =
                without_gil([&] { return self.robot().read_base_pose(world_H_base, mode); });
            return py::make_tuple(world_H_base, stamp);
          },
          arg("mode") = ReadMode::latest, "(world_H_base 4x4, Stamp)")
      .def(
          "set_estimation_parameter",
          [](PythonInterface& self, const std::string& name, double value) {
            self.robot().set_estimation_parameter(name, value);
          },
          arg("name"), arg("value"));
}

void bind_actuators(py::class_<PythonInterface>& interface) {
  using py::arg;
  interface
      .def(
          "set_control_mode",
          [](PythonInterface& self, ControlMode mode, std::optional<int> joint) {
            if (joint) {
              self.robot().set_control_mode(mode, *joint);
            } else {
              self.robot().set_control_mode(mode);
            }
          },
          arg("mode"), arg("joint") = py::none(),
          "every controlled joint, or one (its index in joint_list)")
      .def(
          "set_control_reference",
          [](PythonInterface& self, const ConstVector& reference) {
            self.robot().set_control_reference(reference);
          },
          arg("reference"), "references of every controlled joint (size dofs)")
      .def(
          "set_control_reference",
          [](PythonInterface& self, double reference, int joint) {
            self.robot().set_control_reference(reference, joint);
          },
          arg("reference"), arg("joint"))
      .def(
          "set_control_parameter",
          [](PythonInterface& self, ControlParameter parameter, const ConstVector& values) {
            self.robot().set_control_parameter(parameter, values);
          },
          arg("parameter"), arg("values"))
      .def(
          "set_control_parameter",
          [](PythonInterface& self, ControlParameter parameter, double value, int joint) {
            self.robot().set_control_parameter(parameter, value, joint);
          },
          arg("parameter"), arg("value"), arg("joint"));
}

void bind_model_element(py::class_<PythonInterface>& interface) {
  using py::arg;
  const auto none = py::none();
  interface
      .def(
          "joint_limits",
          [](PythonInterface& self, int joint) {
            const JointLimits limits = self.robot().joint_limits(joint);
            py::dict result;
            result["position_min"] = limits.position_min;
            result["position_max"] = limits.position_max;
            result["velocity_max"] = limits.velocity_max;
            result["effort_max"] = limits.effort_max;
            return result;
          },
          arg("joint"))
      .def(
          "frame_index",
          [](PythonInterface& self, const std::string& frame) {
            return self.robot().frame_index(frame);
          },
          arg("frame"))
      .def(
          "frame_pose",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             int frame) {
            Transform world_H_frame;
            py::gil_scoped_release release;  // a remote model asks the model service
            self.robot().frame_pose(q, world_H_base, frame, world_H_frame);
            return world_H_frame;
          },
          arg("q"), arg("world_H_base"), arg("frame"))
      .def(
          "jacobian",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base, int frame,
             const py::object& out) {
            ColumnMajorArray J = matrix_out(out, 6, self.nv(), "jacobian");
            self.robot().jacobian(q, world_H_base, frame, as_matrix(J));
            return J;
          },
          arg("q"), arg("world_H_base"), arg("frame"), arg("out") = none)
      .def(
          "dj_nu",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const ConstVector& dq, const ConstVector& base_velocity, int frame,
             const py::object& out) {
            Array result = vector_out(out, 6, "dj_nu");
            self.robot().dj_nu(q, world_H_base, dq, base_velocity, frame, as_vector(result));
            return result;
          },
          arg("q"), arg("world_H_base"), arg("dq"), arg("base_velocity"), arg("frame"),
          arg("out") = none)
      .def(
          "mass_matrix",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const py::object& out) {
            ColumnMajorArray M = matrix_out(out, self.nv(), self.nv(), "mass_matrix");
            self.robot().mass_matrix(q, world_H_base, as_matrix(M));
            return M;
          },
          arg("q"), arg("world_H_base"), arg("out") = none)
      .def(
          "bias_forces",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const ConstVector& dq, const ConstVector& base_velocity,
             const Eigen::Vector3d& gravity, const py::object& out) {
            Array h = vector_out(out, self.nv(), "bias_forces");
            self.robot().bias_forces(q, world_H_base, dq, base_velocity, gravity, as_vector(h));
            return h;
          },
          arg("q"), arg("world_H_base"), arg("dq"), arg("base_velocity"),
          arg("gravity") = kGravity, arg("out") = none)
      .def(
          "gravity_forces",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const Eigen::Vector3d& gravity, const py::object& out) {
            Array g = vector_out(out, self.nv(), "gravity_forces");
            self.robot().gravity_forces(q, world_H_base, gravity, as_vector(g));
            return g;
          },
          arg("q"), arg("world_H_base"), arg("gravity") = kGravity, arg("out") = none)
      .def(
          "inverse_dynamics",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const ConstVector& dq, const ConstVector& base_velocity, const ConstVector& ddq,
             const ConstVector& base_acceleration, const Eigen::Vector3d& gravity,
             const py::object& out) {
            Array tau = vector_out(out, self.nv(), "inverse_dynamics");
            self.robot().inverse_dynamics(q, world_H_base, dq, base_velocity, ddq,
                                          base_acceleration, gravity, as_vector(tau));
            return tau;
          },
          arg("q"), arg("world_H_base"), arg("dq"), arg("base_velocity"), arg("ddq"),
          arg("base_acceleration"), arg("gravity") = kGravity, arg("out") = none)
      .def(
          "centroidal_momentum",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const ConstVector& dq, const ConstVector& base_velocity, const py::object& out) {
            Array h = vector_out(out, 6, "centroidal_momentum");
            self.robot().centroidal_momentum(q, world_H_base, dq, base_velocity, as_vector(h));
            return h;
          },
          arg("q"), arg("world_H_base"), arg("dq"), arg("base_velocity"), arg("out") = none)
      .def(
          "centroidal_momentum_matrix",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const py::object& out) {
            ColumnMajorArray A = matrix_out(out, 6, self.nv(), "centroidal_momentum_matrix");
            self.robot().centroidal_momentum_matrix(q, world_H_base, as_matrix(A));
            return A;
          },
          arg("q"), arg("world_H_base"), arg("out") = none)
      .def(
          "com",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base) {
            Eigen::Vector3d c;
            self.robot().com(q, world_H_base, c);
            return c;
          },
          arg("q"), arg("world_H_base"))
      .def(
          "com_jacobian",
          [](PythonInterface& self, const ConstVector& q, const Transform& world_H_base,
             const py::object& out) {
            ColumnMajorArray J = matrix_out(out, 3, self.nv(), "com_jacobian");
            self.robot().com_jacobian(q, world_H_base, as_matrix(J));
            return J;
          },
          arg("q"), arg("world_H_base"), arg("out") = none);
}

}  // namespace

void bind_interface(py::module_& module) {
  using py::arg;
  bind_vocabulary(module);
  py::class_<PythonInterface> interface(
      module, "DdsInterface",
      "The whole-body interface of a robot over DDS (make_dds_interface). Keyword options as "
      "DdsInterfaceOptions; joints: the controlled joints (add_joints), in the order of every "
      "joint vector. Joining: deploy (a deploy file), domain_id, discovery, peers, interfaces, "
      "discovery_server, qos_file, security, identity, above the WBI_* environment "
      "(dds/README.md). Call init() before reading.");
  interface
      .def(py::init(&make_interface), arg("robot"), arg("urdf") = "", arg("joints") = py::none(),
           arg("controller") = "controller", arg("model") = "local",
           arg("locked_positions") = std::map<std::string, double>{}, arg("max_age_s") = 0.1,
           arg("blocking_read_timeout_s") = 1.0, arg("model_timeout_s") = 0.2,
           arg("domain_id") = py::none(), arg("discovery") = py::none(),
           arg("participant_name") = "wbi_python", arg("qos_file") = py::none(),
           arg("armature") = std::map<std::string, double>{}, arg("deploy") = py::none(),
           arg("peers") = py::none(), arg("interfaces") = py::none(),
           arg("discovery_server") = py::none(), arg("security") = py::none(),
           arg("identity") = py::none(), arg("claim") = "claim")
      .def(
          "add_joints",
          [](PythonInterface& self, const IdList& joints) { self.robot().add_joints(joints); },
          arg("joints"))
      .def(
          "init",
          [](PythonInterface& self, double timeout_s) {
            py::gil_scoped_release release;
            self.robot().init(milliseconds(timeout_s));
          },
          arg("timeout_s") = 10.0,
          "waits for the robot's components; raises TimeoutError naming the missing ones")
      .def("close", [](PythonInterface& self) { self.robot().close(); })
      .def_property_readonly("dofs", [](PythonInterface& self) { return self.robot().dofs(); })
      .def_property_readonly("joint_list",
                             [](PythonInterface& self) { return self.robot().joint_list(); })
      .def_property_readonly("frame_list",
                             [](PythonInterface& self) { return self.robot().frame_list(); })
      .def(
          "sensor_list",
          [](PythonInterface& self, SensorKind kind) { return self.robot().sensor_list(kind); },
          arg("kind"))
      .def_property_readonly(
          "external_wrench_links",
          [](PythonInterface& self) { return self.robot().external_wrench_links(); },
          "links with an external-wrench estimate (EstimateKind.external_wrench), init()'s");
  bind_reads(interface);
  bind_actuators(interface);
  bind_model_element(interface);
}

}  // namespace wbi::python
