// Configuration of the simulation backend (SimBackend). Every field has its
// default here; components/sim/README.md explains each one. It can be built in
// code or parsed from YAML (parse_sim_config / sim_config_from_yaml); unknown
// keys, wrong types and bad values are errors that name the key.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace YAML {
class Node;
}

namespace wbi::sim {

struct ContactPointConfig {
  std::string link;                                    // URDF link (frame) the point is fixed to
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // in the link frame [m]
};

struct ContactConfig {
  // "auto": on for floating-base robots, off for fixed-base ones.
  enum class Enable { kAuto, kOn, kOff } enable = Enable::kAuto;
  double stiffness = 3.0e4;  // normal spring per point [N/m]
  double damping = 1.0e2;  // normal damper per point [N·s/m] (only while penetrating; no adhesion)
  double friction = 0.8;   // Coulomb coefficient μ
  // Tangential model: kSpring = anchored spring-damper with a stick/slip limit
  // |F_t| ≤ μ F_n (a standing robot does not creep); kRegularized = −μ F_n v/√(|v|²+v_s²).
  enum class Tangential { kSpring, kRegularized } tangential = Tangential::kSpring;
  double tangential_stiffness = 3.0e4;  // [N/m] per point (kSpring)
  double tangential_damping = 1.0e2;    // [N·s/m] per point (kSpring, while sticking)
  double slip_velocity = 1.0e-3;        // v_s [m/s] (kRegularized)
  // Links whose <collision> boxes give the contact points (the 4 corners of the
  // bottom face, −z of the box). Empty: every link with a <collision> box.
  std::vector<std::string> links;
  std::vector<ContactPointConfig> points;  // extra points, configured per link
};

struct JointLimitConfig {
  // Stiff spring-damper beyond the URDF position limits. ≤ 0: automatic, the
  // stiffest stable one for each joint: k = m_j (0.5/h)², d = m_j/h (h: substep,
  // m_j = 1/(M⁻¹)_jj: effective inertia of joint j at the initial posture).
  double stiffness = 0.0;  // [N·m/rad]
  double damping = 0.0;    // [N·m·s/rad]
};

struct EncoderConfig {
  double counts_per_revolution = 16384.0;  // 2^14; ≤ 0: no quantisation
  double position_noise = 0.0;             // σ [rad], added before quantisation
  double velocity_noise = 0.0;             // σ [rad/s]
  double torque_noise = 0.0;               // σ [N·m]
};

struct ImuConfig {
  std::string name;
  std::string frame;         // URDF link (or frame) the IMU is fixed to; its axes are the IMU axes
  double gyro_noise = 0.0;   // σ [rad/s]
  double accel_noise = 0.0;  // σ [m/s²]
};

struct ForceTorqueConfig {
  std::string name;
  std::string joint;          // a URDF *fixed* joint; sensor frame = its child link frame
  double force_noise = 0.0;   // σ [N]
  double torque_noise = 0.0;  // σ [N·m]
};

struct PushConfig {
  std::string link;                                 // URDF link (frame) the force acts on
  double start = 0.0;                               // [s] simulation time
  double duration = 0.1;                            // [s]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // [N], world axes
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // application point in the link frame [m]
};

// DC motor behind every joint, used for PWM commands:
//   τ = k_t (V·pwm − k_e q̇) / R, saturated at the joint's effort limit.
// k_t and k_e are referred to the joint (gearbox included).
struct MotorConfig {
  double voltage = 24.0;         // supply V [V]
  double resistance = 1.0;       // winding R [Ω]
  double torque_constant = 0.0;  // k_t [N·m/A]; ≤ 0: effort_limit·R/V (stall torque = effort limit)
  double back_emf = 0.0;         // k_e [V·s/rad]; ≤ 0: = k_t
};

struct SimConfig {
  std::string urdf;         // URDF file (the only required field)
  bool fixed_base = false;  // force a fixed base (a root named "world" is fixed anyway)
  double step = 1.0e-3;     // control period h_c [s]: one step() (default 1 kHz)
  // Integration substeps per step (h = step / substeps). 2 by default: the
  // explicit dissipative forces on the light distal joints of a robot without
  // rotor inertia need h ≤ 0.5 ms (README.md, "Stability").
  int substeps = 2;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};

  std::map<std::string, double> initial_joint_positions;         // by joint name; the rest 0
  Eigen::Vector3d initial_base_position{0.0, 0.0, 0.0};          // [m]
  Eigen::Vector4d initial_base_orientation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z), normalised
  // Shift the initial base height so that the lowest contact point touches z = 0.
  bool place_on_ground = false;

  // Armature by joint name [kg·m² or kg]: rotor inertia reflected through the gear
  // ratio, added to the diagonal of M (wbi::model::LoadOptions::armature). Default none.
  std::map<std::string, double> armature;
  bool joint_damping = true;        // viscous damping from URDF <dynamics damping>
  bool joint_friction = true;       // Coulomb friction from URDF <dynamics friction>
  double friction_velocity = 0.01;  // smoothing: τ_f = −F_c tanh(q̇ / v_f) [rad/s]
  JointLimitConfig joint_limits;

  ContactConfig contact;
  EncoderConfig encoders;
  MotorConfig motor;
  std::vector<ImuConfig> imus;
  std::vector<ForceTorqueConfig> force_torque;
  std::vector<PushConfig> pushes;
  std::uint64_t seed = 0;  // noise generator seed
};

// Parse a YAML document (the keys of SimConfig, see README.md). `context` names
// the source in error messages (e.g. the file). Throws std::invalid_argument.
SimConfig parse_sim_config(std::string_view yaml_text, const std::string& context = "<string>");
SimConfig load_sim_config_file(const std::string& path);
// From an already-parsed node (the caller includes <yaml-cpp/yaml.h>).
SimConfig sim_config_from_yaml(const YAML::Node& node, const std::string& context = "<yaml>");

}  // namespace wbi::sim
