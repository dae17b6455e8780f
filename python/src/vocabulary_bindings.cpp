// The whole-body interface's vocabulary for Python: ControlMode, SensorKind,
// EstimateKind, ReadMode, Stamp, RobotState and the errors (wbi.Error, ...).
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <wbi/dds_interface.hpp>

#include "bindings.hpp"

namespace wbi::python {

namespace py = pybind11;

void bind_vocabulary(py::module_& module) {
  py::enum_<ControlMode>(module, "ControlMode")
      .value("idle", ControlMode::idle)
      .value("position", ControlMode::position)
      .value("position_direct", ControlMode::position_direct)
      .value("velocity", ControlMode::velocity)
      .value("torque", ControlMode::torque)
      .value("pwm", ControlMode::pwm);
  py::enum_<ControlParameter>(module, "ControlParameter")
      .value("kp", ControlParameter::kp)
      .value("ki", ControlParameter::ki)
      .value("kd", ControlParameter::kd)
      .value("reference_speed", ControlParameter::reference_speed);
  py::enum_<SensorKind>(module, "SensorKind")
      .value("encoder_position", SensorKind::encoder_position)
      .value("encoder_velocity", SensorKind::encoder_velocity)
      .value("encoder_acceleration", SensorKind::encoder_acceleration)
      .value("joint_torque", SensorKind::joint_torque)
      .value("motor_pwm", SensorKind::motor_pwm)
      .value("imu", SensorKind::imu)
      .value("force_torque", SensorKind::force_torque)
      .value("accelerometer", SensorKind::accelerometer)
      .value("gyroscope", SensorKind::gyroscope);
  py::enum_<EstimateKind>(module, "EstimateKind")
      .value("joint_position", EstimateKind::joint_position)
      .value("joint_velocity", EstimateKind::joint_velocity)
      .value("joint_acceleration", EstimateKind::joint_acceleration)
      .value("joint_torque", EstimateKind::joint_torque)
      .value("base_pose", EstimateKind::base_pose)
      .value("base_velocity", EstimateKind::base_velocity)
      .value("base_acceleration", EstimateKind::base_acceleration)
      .value("force_torque", EstimateKind::force_torque)
      .value("external_wrench", EstimateKind::external_wrench);
  py::enum_<ReadMode>(module, "ReadMode")
      .value("latest", ReadMode::latest)
      .value("blocking", ReadMode::blocking);
  py::class_<Stamp>(module, "Stamp", "When and how fresh the data of a read is")
      .def_readonly("source_ns", &Stamp::source_ns, "source stamp of the sample [ns]")
      .def_readonly("seq", &Stamp::seq, "sequence number of the sample")
      .def_readonly("age_s", &Stamp::age_s, "time since the sample arrived [s]")
      .def("__repr__", [](const Stamp& s) {
        return "Stamp(source_ns=" + std::to_string(s.source_ns) + ", seq=" + std::to_string(s.seq) +
               ", age_s=" + std::to_string(s.age_s) + ")";
      });
  // Its arrays are read-only numpy views on the C++ storage, not copies: a
  // loop that reads into one RobotState sees each tick's values through the
  // same arrays, and nothing is allocated per tick.
  py::class_<RobotState>(module, "RobotState",
                         "q, dq, ddq, base pose and velocity of one estimate "
                         "(DdsInterface.robot_state(), DdsInterface.read_robot_state)")
      .def_readonly("q", &RobotState::q, "joint positions (dofs,), a view")
      .def_readonly("dq", &RobotState::dq, "joint velocities (dofs,), a view")
      .def_readonly("ddq", &RobotState::ddq, "joint accelerations (dofs,), a view")
      .def_readonly("world_H_base", &RobotState::world_H_base, "base pose (4, 4), a view")
      .def_readonly("base_velocity", &RobotState::base_velocity,
                    "(linear, angular) base velocity, world axes (6,), a view")
      .def_readonly("stamp", &RobotState::stamp, "the Stamp of the estimate");
  // Subclasses of RuntimeError, so that `except RuntimeError` still catches them.
  static py::exception<Error> error(module, "Error", PyExc_RuntimeError);
  static py::exception<StaleDataError> stale(module, "StaleDataError", error.ptr());
  static py::exception<TimeoutError> timeout(module, "TimeoutError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) {
        std::rethrow_exception(p);
      }
    } catch (const TimeoutError& e) {
      timeout(e.what());
    } catch (const StaleDataError& e) {
      stale(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

}  // namespace wbi::python
