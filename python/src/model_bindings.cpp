// wbi.Model: the model library (wbi::model) for Python. One Model owns its
// immutable wbi::model::Model and one Data workspace. Conventions are the
// library's (model_service/README.md): q has nq entries (floating base:
// position, quaternion w,x,y,z, joints), ν has nv (mixed: ṗ_B, ω_B in world
// axes, q̇); 6D vectors linear first. Inputs bind to float64 numpy arrays
// without copying; results are new arrays, or written into `out=`.
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <wbi/model/algorithms.hpp>
#include <wbi/model/configuration.hpp>
#include <wbi/model/urdf.hpp>

#include "bindings.hpp"
#include "numpy_out.hpp"

namespace wbi::python {

namespace {

namespace wm = wbi::model;
using ConstVector = Eigen::Ref<const Eigen::VectorXd>;
using FrameKey = std::variant<int, std::string>;  // a frame by index or by name

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

class PythonModel {
 public:
  explicit PythonModel(wm::Model model) : model_(std::move(model)), data_(model_) {}

  const wm::Model& model() const { return model_; }
  wm::Data& data() { return data_; }

  int frame(const FrameKey& key) const {
    if (const auto* name = std::get_if<std::string>(&key)) {
      return model_.frame_id(*name);  // throws invalid_argument naming it
    }
    const int index = std::get<int>(key);
    if (index < 0 || index >= model_.n_frames()) {
      throw py::index_error("frame index " + std::to_string(index) + " out of range [0, " +
                            std::to_string(model_.n_frames()) + ")");
    }
    return index;
  }

  // {frame: (force, moment about the frame origin), world axes} → library wrenches.
  std::vector<wm::ExternalWrench> wrenches(const py::object& given) const {
    std::vector<wm::ExternalWrench> result;
    if (given.is_none()) {
      return result;
    }
    for (const auto& [key, value] : given.cast<py::dict>()) {
      wm::ExternalWrench wrench;
      wrench.frame = frame(key.cast<FrameKey>());
      wrench.wrench = value.cast<Eigen::Matrix<double, 6, 1>>();
      result.push_back(wrench);
    }
    return result;
  }

 private:
  wm::Model model_;
  wm::Data data_;
};

// Copies a library result into the output array (new or the caller's).
template <typename Result>
Array vector_result(const Result& result, const py::object& out, const char* what) {
  Array array = vector_out(out, result.size(), what);
  as_vector(array) = result;
  return array;
}

template <typename Result>
ColumnMajorArray matrix_result(const Result& result, const py::object& out, const char* what) {
  ColumnMajorArray array = matrix_out(out, result.rows(), result.cols(), what);
  as_matrix(array) = result;
  return array;
}

PythonModel from_urdf(const std::string& path,
                      const std::optional<std::vector<std::string>>& joints, bool fixed_base,
                      const std::map<std::string, double>& locked_positions,
                      const std::map<std::string, double>& armature) {
  wm::LoadOptions options;
  options.fixed_base = fixed_base;
  options.joints = joints.value_or(std::vector<std::string>{});
  options.locked_positions = locked_positions;
  options.armature = armature;
  return PythonModel(wm::load_urdf_file(path, options));
}

py::dict joint_limits(const wm::Model& model) {
  const auto array = [](const std::vector<double>& values) {
    return Array(static_cast<py::ssize_t>(values.size()), values.data());
  };
  py::dict limits;
  limits["position_min"] = array(model.joint_lower);
  limits["position_max"] = array(model.joint_upper);
  limits["velocity_max"] = array(model.joint_velocity_limit);
  limits["effort_max"] = array(model.joint_effort_limit);
  return limits;
}

}  // namespace

void bind_model(py::module_& module) {
  using py::arg;
  const auto none = py::none();
  py::class_<PythonModel>(module, "Model",
                          "A robot's kinematic tree from a URDF, with its own workspace.\n"
                          "q: nq = 7 + n (floating base: position, quaternion w,x,y,z, joints) "
                          "or n (fixed base); nu: nv = 6 + n (mixed: base linear and angular "
                          "velocity in world axes, joint velocities) or n.")
      .def_static("from_urdf", &from_urdf, arg("path"), arg("joints") = none,
                  arg("fixed_base") = false,
                  arg("locked_positions") = std::map<std::string, double>{},
                  arg("armature") = std::map<std::string, double>{},
                  "Loads a URDF. joints: keep these, in this order (reduced model), the other "
                  "movable joints locked at locked_positions (default 0). armature: rotor "
                  "inertia by joint name [kg m^2 or kg], on M's diagonal, in forward and "
                  "inverse dynamics (MuJoCo's convention; model_service/README.md).")
      .def_property_readonly("name", [](const PythonModel& m) { return m.model().name; })
      .def_property_readonly("floating_base",
                             [](const PythonModel& m) { return m.model().floating_base; })
      .def_property_readonly("nq", [](const PythonModel& m) { return m.model().nq; })
      .def_property_readonly("nv", [](const PythonModel& m) { return m.model().nv; })
      .def_property_readonly("n_joints", [](const PythonModel& m) { return m.model().n_joints; })
      .def_property_readonly("total_mass",
                             [](const PythonModel& m) { return m.model().total_mass; })
      .def_property_readonly("joint_names",
                             [](const PythonModel& m) { return m.model().joint_name; })
      .def_property_readonly("frame_names",
                             [](const PythonModel& m) { return m.model().frame_name; })
      .def_property_readonly(
          "joint_limits", [](const PythonModel& m) { return joint_limits(m.model()); },
          "dict of arrays position_min, position_max, velocity_max, effort_max (±inf: none)")
      .def(
          "frame_index",
          [](const PythonModel& m, const std::string& frame) { return m.frame(frame); },
          arg("frame"))
      .def(
          "joint_index",
          [](const PythonModel& m, const std::string& joint) { return m.model().joint_id(joint); },
          arg("joint"))
      .def(
          "neutral_configuration",
          [](const PythonModel& m) {
            return Eigen::VectorXd(wm::neutral_configuration(m.model()));
          },
          "q with the base at the origin (identity orientation) and every joint at 0")
      .def(
          "configuration",
          [](const PythonModel& m, const Eigen::Matrix4d& world_H_base,
             const Eigen::VectorXd& joint_positions) {
            return wm::make_configuration(m.model(), world_H_base, joint_positions);
          },
          arg("world_H_base"), arg("joint_positions"),
          "q from a 4x4 base pose and the joint positions")
      .def(
          "mass_matrix",
          [](PythonModel& m, const ConstVector& q, const py::object& out) {
            return matrix_result(wm::mass_matrix(m.model(), m.data(), q), out, "mass_matrix");
          },
          arg("q"), arg("out") = none, "M(q), nv x nv")
      .def(
          "bias_forces",
          [](PythonModel& m, const ConstVector& q, const ConstVector& nu,
             const Eigen::Vector3d& gravity, const py::object& out) {
            return vector_result(wm::bias_forces(m.model(), m.data(), q, nu, gravity), out,
                                 "bias_forces");
          },
          arg("q"), arg("nu"), arg("gravity") = kGravity, arg("out") = none,
          "h = C(q, nu) nu + G(q), nv")
      .def(
          "gravity_forces",
          [](PythonModel& m, const ConstVector& q, const Eigen::Vector3d& gravity,
             const py::object& out) {
            return vector_result(wm::gravity_forces(m.model(), m.data(), q, gravity), out,
                                 "gravity_forces");
          },
          arg("q"), arg("gravity") = kGravity, arg("out") = none, "G(q), nv")
      .def(
          "inverse_dynamics",
          [](PythonModel& m, const ConstVector& q, const ConstVector& nu, const ConstVector& dnu,
             const Eigen::Vector3d& gravity, const py::object& wrenches, const py::object& out) {
            const auto external = m.wrenches(wrenches);
            return vector_result(
                wm::inverse_dynamics(m.model(), m.data(), q, nu, dnu, gravity, external), out,
                "inverse_dynamics");
          },
          arg("q"), arg("nu"), arg("dnu"), arg("gravity") = kGravity, arg("wrenches") = none,
          arg("out") = none,
          "tau = M dnu + h - sum J^T w, nv; wrenches: {frame: (force, moment about the frame "
          "origin), world axes}")
      .def(
          "forward_dynamics",
          [](PythonModel& m, const ConstVector& q, const ConstVector& nu, const ConstVector& tau,
             const Eigen::Vector3d& gravity, const py::object& wrenches, const py::object& out) {
            const auto external = m.wrenches(wrenches);
            return vector_result(
                wm::forward_dynamics(m.model(), m.data(), q, nu, tau, gravity, external), out,
                "forward_dynamics");
          },
          arg("q"), arg("nu"), arg("tau"), arg("gravity") = kGravity, arg("wrenches") = none,
          arg("out") = none, "dnu = M^-1 (tau + sum J^T w - h), nv (ABA)")
      .def(
          "frame_pose",
          [](PythonModel& m, const ConstVector& q, const FrameKey& frame) {
            const int id = m.frame(frame);
            wm::forward_kinematics(m.model(), m.data(), q);
            return Eigen::Matrix4d(wm::frame_pose(m.model(), m.data(), id));
          },
          arg("q"), arg("frame"), "world_H_frame, 4x4")
      .def(
          "jacobian",
          [](PythonModel& m, const ConstVector& q, const FrameKey& frame, const py::object& out) {
            const int id = m.frame(frame);
            return matrix_result(wm::frame_jacobian(m.model(), m.data(), q, id), out, "jacobian");
          },
          arg("q"), arg("frame"), arg("out") = none,
          "6 x nv: nu -> (linear, angular) velocity of the frame origin, world axes")
      .def(
          "dj_nu",
          [](PythonModel& m, const ConstVector& q, const ConstVector& nu, const FrameKey& frame) {
            const int id = m.frame(frame);
            wm::forward_velocity_kinematics(m.model(), m.data(), q, nu);
            return Eigen::Matrix<double, 6, 1>(
                wm::frame_bias_acceleration(m.model(), m.data(), id));
          },
          arg("q"), arg("nu"), arg("frame"), "dJ/dt nu of the frame, 6")
      .def(
          "com",
          [](PythonModel& m, const ConstVector& q) {
            return Eigen::Vector3d(wm::center_of_mass(m.model(), m.data(), q));
          },
          arg("q"), "centre of mass in the world, 3")
      .def(
          "com_jacobian",
          [](PythonModel& m, const ConstVector& q, const py::object& out) {
            return matrix_result(wm::com_jacobian(m.model(), m.data(), q), out, "com_jacobian");
          },
          arg("q"), arg("out") = none, "3 x nv")
      .def(
          "com_bias_acceleration",
          [](PythonModel& m, const ConstVector& q, const ConstVector& nu) {
            return Eigen::Vector3d(wm::com_bias_acceleration(m.model(), m.data(), q, nu));
          },
          arg("q"), arg("nu"), "dJ_com/dt nu, 3")
      .def(
          "centroidal_momentum",
          [](PythonModel& m, const ConstVector& q, const ConstVector& nu) {
            return Eigen::Matrix<double, 6, 1>(wm::centroidal_momentum(m.model(), m.data(), q, nu));
          },
          arg("q"), arg("nu"), "(linear, angular about the CoM), world axes, 6")
      .def(
          "centroidal_momentum_matrix",
          [](PythonModel& m, const ConstVector& q, const py::object& out) {
            return matrix_result(wm::centroidal_momentum_matrix(m.model(), m.data(), q), out,
                                 "centroidal_momentum_matrix");
          },
          arg("q"), arg("out") = none, "A_G, 6 x nv")
      .def("__repr__", [](const PythonModel& m) {
        return "<wbi.Model '" + m.model().name + "': " + std::to_string(m.model().n_joints) +
               " joints, " + (m.model().floating_base ? "floating" : "fixed") + " base>";
      });
}

}  // namespace wbi::python
