// A robot configuration: the robot (URDF, posture, contact geometry, joint
// dynamics, sensors) and the options of each simulation engine, in one YAML
// schema (robot_side/robot_config/README.md lists every key). Pure data: no
// engine, no DDS. Every error in a file is one line "file:line: key: what".
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <wbi/vocabulary/contact_shape.hpp>
#include <wbi/vocabulary/integrator.hpp>

namespace wbi::robot_config {

// Collision geometry fixed to a link, placed in the link frame. The own plant
// (wbi::sim) turns a box into the 4 corners of its −z face, a sphere into one
// point of that radius and a capsule into two (its end spheres).
struct ContactGeometry {
  std::string link;  // URDF link (or frame)
  ContactShape shape = ContactShape::box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box: full extents [m]
  double radius = 0.0;                             // sphere, capsule [m]
  double length =
      0.0;  // capsule: between the centres of its end spheres, along the geometry's z [m]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      // geometry origin in the link frame [m]
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // geometry axes in the link frame
  // Coulomb μ against the ground; < 0 (not given): the ground's, filled in by
  // complete_from_urdf().
  double friction = -1.0;
};

// One joint: its passive dynamics, referred to the joint (after the gearbox),
// and the gains of its position loop (what a motor-control board is set to).
struct JointDynamics {
  double armature = 0.0;  // rotor inertia × gear ratio² [kg·m²] (kg for a prismatic joint)
  double damping = 0.0;   // viscous [N·m·s/rad]
  double friction = 0.0;  // Coulomb [N·m]
  // Position PD of the joint controller (modes POSITION, POSITION_DIRECT,
  // VELOCITY and the hold of uncommanded joints); 0: its default
  // (wbi::actuation::JointController, from the effort limit).
  double kp = 0.0;  // [N·m/rad]
  double kd = 0.0;  // [N·m·s/rad]
};

struct GroundConfig {
  double height = 0.0;    // z of the ground plane, world [m]
  double friction = 0.8;  // Coulomb μ of contacts that give none
};

struct ImuConfig {
  std::string name;
  std::string frame;         // URDF link (or frame); its axes are the IMU axes
  double gyro_noise = 0.0;   // σ [rad/s]
  double accel_noise = 0.0;  // σ [m/s²]
};

struct ForceTorqueConfig {
  std::string name;
  std::string joint;          // a URDF *fixed* joint; sensor frame = its child link frame
  double force_noise = 0.0;   // σ [N]
  double torque_noise = 0.0;  // σ [N·m]
};

// Which joints have a joint-torque sensor ("joint_torque_sensors:"). A robot
// publishes a joint torque only for those (idl/sensors.idl, SensorSample).
struct JointTorqueSensors {
  // kAll: every joint (the default); kNone: no joint; kListed: the joints of `joints`.
  enum class Which { kAll, kNone, kListed } which = Which::kAll;
  std::vector<std::string> joints;  // kListed: movable joints of the URDF, each once

  // Whether `joint` has a sensor.
  bool has(const std::string& joint) const;
};

// An external force for a while (a scenario, the same in every engine).
struct PushConfig {
  std::string link;                                 // URDF link (frame) the force acts on
  double start = 0.0;                               // [s] simulation time
  double duration = 0.1;                            // [s]
  Eigen::Vector3d force = Eigen::Vector3d::Zero();  // [N], world axes
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // application point in the link frame [m]
};

// ---- the own plant (wbi::sim, "wbi:" section); robot_side/sim/README.md ----

struct ContactModel {
  // "auto": on for floating-base robots, off for fixed-base ones.
  enum class Enable { kAuto, kOn, kOff } enable = Enable::kAuto;
  double stiffness = 3.0e4;  // normal spring per point [N/m]
  double damping = 1.0e2;  // normal damper per point [N·s/m] (only while penetrating; no adhesion)
  // Tangential model: kSpring = anchored spring-damper with a stick/slip limit
  // |F_t| ≤ μ F_n (a standing robot does not creep); kRegularized = −μ F_n v/√(|v|²+v_s²).
  enum class Tangential { kSpring, kRegularized } tangential = Tangential::kSpring;
  double tangential_stiffness = 3.0e4;  // [N/m] per point (kSpring)
  double tangential_damping = 1.0e2;    // [N·s/m] per point (kSpring, while sticking)
  double slip_velocity = 1.0e-3;        // v_s [m/s] (kRegularized)
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

// DC motor behind every joint, used for PWM commands:
//   τ = k_t (V·pwm − k_e q̇) / R, saturated at the joint's effort limit.
// k_t and k_e are referred to the joint (gearbox included).
struct MotorConfig {
  double voltage = 24.0;         // supply V [V]
  double resistance = 1.0;       // winding R [Ω]
  double torque_constant = 0.0;  // k_t [N·m/A]; ≤ 0: effort_limit·R/V (stall torque = effort limit)
  double back_emf = 0.0;         // k_e [V·s/rad]; ≤ 0: = k_t
};

struct WbiOptions {
  double step = 1.0e-3;  // control period h_c [s]: one step() (default 1 kHz)
  // Integration substeps per step (h = step / substeps). 2 by default: the
  // explicit dissipative forces on the light distal joints of a robot without
  // rotor inertia need h ≤ 0.5 ms (robot_side/sim/README.md, "Stability").
  int substeps = 2;
  double friction_velocity = 0.01;  // smoothing: τ_f = −F_c tanh(q̇ / v_f) [rad/s]
  JointLimitConfig joint_limits;
  ContactModel contact;
  EncoderConfig encoders;
  MotorConfig motor;
  std::uint64_t seed = 0;  // noise generator seed
};

// ---- MuJoCo ("mujoco:" section), consumed by the MuJoCo backend ----

struct MujocoOptions {
  double timestep = 5.0e-4;  // mjOption.timestep: one mj_step [s]
  int substeps = 2;          // mj_step per control period (period = timestep × substeps)
  Integrator integrator = Integrator::implicit;
  std::array<double, 2> solref{0.02, 1.0};  // contact (timeconst [s], dampratio), or (−k, −b)
  std::array<double, 5> solimp{0.9, 0.95, 0.001, 0.5, 2.0};  // (dmin, dmax, width [m], mid, power)
  enum class Cone { kPyramidal, kElliptic } cone = Cone::kPyramidal;
  double impratio = 1.0;  // frictional-to-normal impedance ratio (> 0)
  // Joint Coulomb friction (joints: friction): kTorque = the own plant's smoothed
  // model −F_c tanh(q̇ / wbi.friction_velocity) as an applied torque; kConstraint =
  // MuJoCo's frictionloss, one constraint row per joint (stiction, slower).
  enum class JointFriction { kTorque, kConstraint } joint_friction = JointFriction::kTorque;
};

struct RobotConfig {
  std::string urdf;         // URDF file (the only required key); absolute after loading a file
  bool fixed_base = false;  // force a fixed base (a root named "world" is fixed anyway)
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};

  std::map<std::string, double> initial_joint_positions;         // by joint name; the rest 0
  Eigen::Vector3d initial_base_position{0.0, 0.0, 0.0};          // [m]
  Eigen::Vector4d initial_base_orientation{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z), normalised
  // Shift the initial base height so that the lowest contact point touches the ground.
  bool place_on_ground = false;

  GroundConfig ground;
  // Absent or empty: the URDF's <collision> boxes (complete_from_urdf()).
  std::vector<ContactGeometry> contacts;
  // Every model joint after complete_from_urdf() (load/parse call it): the
  // "joints:" entry, else "joints: default:", else URDF <dynamics> (armature 0).
  std::map<std::string, JointDynamics> joints;
  JointTorqueSensors joint_torque_sensors;
  std::vector<ImuConfig> imus;
  std::vector<ForceTorqueConfig> force_torque;
  std::vector<PushConfig> pushes;

  WbiOptions wbi;
  MujocoOptions mujoco;
};

// Parse a YAML document. `context` is the file the text came from: it names the
// source in errors, and a relative `urdf` is relative to its directory. Loads the
// URDF (wbi::model) to check every joint, link and frame name, then
// complete_from_urdf(). Throws std::invalid_argument with one line
// "context:line: key: what".
RobotConfig parse_robot_config(std::string_view yaml_text, const std::string& context);
RobotConfig load_robot_config(const std::string& path);

// For a configuration built in code: `joints` gets every movable joint of the
// URDF that it lacks (URDF <dynamics> damping and friction, armature 0), and
// empty `contacts` the URDF's <collision> boxes, and a contact friction < 0
// the ground's. Idempotent. Throws std::runtime_error when the URDF
// cannot be read.
void complete_from_urdf(RobotConfig& config);

// Armature by joint name (for model::LoadOptions): every joint of `joints`.
std::map<std::string, double> armature_by_joint(const RobotConfig& config);

}  // namespace wbi::robot_config
