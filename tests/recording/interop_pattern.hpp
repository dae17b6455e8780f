// The samples of the interop talker (interop_talker.cpp): three wbi types
// whose every field follows from the robot name and the sequence number, and
// the same values as JSON in the shape a JavaScript OMG-IDL decoder gives
// them (64-bit integers as decimal strings, enums as their numbers, arrays as
// arrays), so that test_record_interop can compare what node decoded.
#pragma once

#include <cstdint>
#include <string>

#include <wbi/msg/description.h>
#include <wbi/msg/sensors.h>
#include <wbi/msg/state.h>
#include <nlohmann/json.hpp>

namespace wbi::test {

inline constexpr std::size_t kInteropJoints = 6;

// Values that are not exact in binary, of both signs, different per seq and index.
inline double interop_value(std::uint64_t seq, std::size_t index) {
  return 0.1 * static_cast<double>(seq) + static_cast<double>(index) / 7.0 - 3.0;
}

inline void fill_header(msg::Header& header, const std::string& robot, std::uint64_t seq) {
  header.robot(robot);
  header.seq(seq);
  header.stamp_ns(1'700'000'000'000'000'000LL + static_cast<std::int64_t>(seq) * 1'000'000);
}

inline void fill_description(msg::RobotDescription& description, const std::string& robot) {
  fill_header(description.header(), robot, 0);
  description.floating_base(true);
  for (std::size_t j = 0; j < kInteropJoints; ++j) {
    description.joint_names().push_back("joint_" + std::to_string(j));
    msg::JointLimits limits;
    limits.position_min(interop_value(0, j));
    limits.position_max(-interop_value(1, j));
    limits.velocity_max(1.5 + static_cast<double>(j));
    limits.effort_max(40.0 / 3.0);
    description.joint_limits().push_back(limits);
  }
  msg::SensorInfo imu;
  imu.name("imu");
  imu.kind(msg::SensorKind::IMU);
  imu.frame("base_link");
  description.sensors().push_back(imu);
  for (const char* side : {"l", "r"}) {
    msg::SensorInfo force_torque;
    force_torque.name(std::string(side) + "_foot_ft");
    force_torque.kind(msg::SensorKind::FORCE_TORQUE);
    force_torque.frame(std::string(side) + "_sole");
    description.sensors().push_back(force_torque);
  }
  description.urdf_path("/models/" + robot + ".urdf");
  description.lockstep(true);
}

inline void fill_sensors(msg::SensorSample& sample, const std::string& robot, std::uint64_t seq) {
  fill_header(sample.header(), robot, seq);
  sample.encoder_position().clear();
  sample.joint_torque().clear();
  sample.motor_pwm().clear();
  for (std::size_t j = 0; j < kInteropJoints; ++j) {
    sample.encoder_position().push_back(interop_value(seq, j));
    sample.joint_torque().push_back(interop_value(seq, 10 + j));
    sample.motor_pwm().push_back(-interop_value(seq, 20 + j) / 100.0);
  }
  msg::ImuReading imu;
  imu.orientation().w(interop_value(seq, 30));
  imu.orientation().x(interop_value(seq, 31));
  imu.orientation().y(interop_value(seq, 32));
  imu.orientation().z(interop_value(seq, 33));
  imu.angular_velocity().x(interop_value(seq, 34));
  imu.angular_velocity().y(interop_value(seq, 35));
  imu.angular_velocity().z(interop_value(seq, 36));
  imu.linear_acceleration().z(9.81);
  sample.imus().assign(1, imu);
  sample.force_torque().resize(2);
  for (std::size_t k = 0; k < 2; ++k) {
    auto& wrench = sample.force_torque()[k].wrench();
    wrench.force().x(interop_value(seq, 40 + 6 * k));
    wrench.force().y(interop_value(seq, 41 + 6 * k));
    wrench.force().z(interop_value(seq, 42 + 6 * k));
    wrench.torque().x(interop_value(seq, 43 + 6 * k));
    wrench.torque().y(interop_value(seq, 44 + 6 * k));
    wrench.torque().z(interop_value(seq, 45 + 6 * k));
  }
}

inline void fill_state(msg::StateEstimate& state, const std::string& robot, std::uint64_t seq) {
  fill_header(state.header(), robot, seq);
  state.q().clear();
  state.dq().clear();
  state.ddq().clear();
  state.tau().clear();
  for (std::size_t j = 0; j < kInteropJoints; ++j) {
    state.q().push_back(interop_value(seq, 50 + j));
    state.dq().push_back(interop_value(seq, 60 + j));
    state.ddq().push_back(interop_value(seq, 70 + j));
    state.tau().push_back(interop_value(seq, 80 + j));
  }
  state.base_pose().position().x(interop_value(seq, 90));
  state.base_pose().position().z(interop_value(seq, 91));
  state.base_pose().orientation().w(1.0);
  for (std::size_t k = 0; k < 6; ++k) {
    state.base_velocity()[k] = interop_value(seq, 92 + k);
    state.base_acceleration()[k] = interop_value(seq, 98 + k);
  }
  state.force_torque().clear();
  state.warnings(static_cast<std::uint32_t>(seq % 3));
  state.external_wrenches().resize(1);
  auto& external = state.external_wrenches()[0];
  external.link("l_sole");
  external.wrench().force().z(interop_value(seq, 110));
  external.wrench().torque().x(interop_value(seq, 111));
  external.contact(true);
  external.loaded(seq % 2 == 0);
  external.valid(true);
}

// --- The same values as the decoder's JSON ---------------------------------

inline nlohmann::json to_json(const msg::Header& header) {
  return {{"robot", header.robot().to_string()},
          {"stamp_ns", std::to_string(header.stamp_ns())},
          {"seq", std::to_string(header.seq())}};
}

inline nlohmann::json to_json(const msg::Vector3& v) {
  return {{"x", v.x()}, {"y", v.y()}, {"z", v.z()}};
}

inline nlohmann::json to_json(const msg::Quaternion& q) {
  return {{"w", q.w()}, {"x", q.x()}, {"y", q.y()}, {"z", q.z()}};
}

inline nlohmann::json to_json(const msg::Wrench& w) {
  return {{"force", to_json(w.force())}, {"torque", to_json(w.torque())}};
}

inline nlohmann::json to_json(const msg::RobotDescription& d) {
  nlohmann::json names = nlohmann::json::array();
  for (const auto& name : d.joint_names()) {
    names.push_back(name.to_string());
  }
  nlohmann::json limits = nlohmann::json::array();
  for (const auto& l : d.joint_limits()) {
    limits.push_back({{"position_min", l.position_min()},
                      {"position_max", l.position_max()},
                      {"velocity_max", l.velocity_max()},
                      {"effort_max", l.effort_max()}});
  }
  nlohmann::json sensors = nlohmann::json::array();
  for (const auto& s : d.sensors()) {
    sensors.push_back({{"name", s.name().to_string()},
                       {"kind", static_cast<std::uint32_t>(s.kind())},
                       {"frame", s.frame().to_string()}});
  }
  return {{"header", to_json(d.header())},
          {"floating_base", d.floating_base()},
          {"joint_names", names},
          {"joint_limits", limits},
          {"sensors", sensors},
          {"urdf_path", d.urdf_path().to_string()},
          {"lockstep", d.lockstep()}};
}

inline nlohmann::json to_json(const msg::SensorSample& s) {
  nlohmann::json imus = nlohmann::json::array();
  for (const auto& imu : s.imus()) {
    imus.push_back({{"orientation", to_json(imu.orientation())},
                    {"angular_velocity", to_json(imu.angular_velocity())},
                    {"linear_acceleration", to_json(imu.linear_acceleration())}});
  }
  nlohmann::json force_torque = nlohmann::json::array();
  for (const auto& ft : s.force_torque()) {
    force_torque.push_back({{"wrench", to_json(ft.wrench())}});
  }
  return {{"header", to_json(s.header())},
          {"encoder_position", s.encoder_position()},
          {"joint_torque", s.joint_torque()},
          {"motor_pwm", s.motor_pwm()},
          {"imus", imus},
          {"force_torque", force_torque}};
}

inline nlohmann::json to_json(const msg::StateEstimate& s) {
  nlohmann::json force_torque = nlohmann::json::array();
  for (const auto& wrench : s.force_torque()) {
    force_torque.push_back(to_json(wrench));
  }
  nlohmann::json external = nlohmann::json::array();
  for (const auto& e : s.external_wrenches()) {
    external.push_back({{"link", e.link().to_string()},
                        {"wrench", to_json(e.wrench())},
                        {"contact", e.contact()},
                        {"loaded", e.loaded()},
                        {"valid", e.valid()}});
  }
  return {{"header", to_json(s.header())},
          {"q", s.q()},
          {"dq", s.dq()},
          {"ddq", s.ddq()},
          {"tau", s.tau()},
          {"base_pose",
           {{"position", to_json(s.base_pose().position())},
            {"orientation", to_json(s.base_pose().orientation())}}},
          {"base_velocity", s.base_velocity()},
          {"base_acceleration", s.base_acceleration()},
          {"force_torque", force_torque},
          {"warnings", s.warnings()},
          {"external_wrenches", external}};
}

}  // namespace wbi::test
