// Writing a wbi::model::Model as MJCF, the XML model format of MuJoCo, so that
// MuJoCo builds the same multibody: the same bodies (fixed joints lumped as the
// model library lumps them), joints, inertias, limits, and the same meaning of
// the floating base's pose. Only text is written: no MuJoCo dependency.
//
//   MjcfOptions options;
//   options.contacts.push_back({.link = "l_sole", .shape = ContactShape::box,
//                               .size = {0.2, 0.1, 0.01}});
//   options.ground.enabled = true;
//   const std::string xml = wbi::mjcf::write_mjcf(model, options);
//
// Conventions and the velocity transform: README.md beside this folder, and
// mujoco_conventions.hpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <wbi/vocabulary/contact_shape.hpp>
#include <wbi/vocabulary/integrator.hpp>

#include "wbi/model/model.hpp"

namespace wbi::mjcf {

// A collision geometry rigidly attached to a link (any frame of the model).
struct ContactGeometry {
  std::string name;  // MJCF geom name; empty: "<link>_contact_<k>"
  std::string link;  // a frame of the model (a URDF link)
  ContactShape shape = ContactShape::box;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box: full edge lengths along x, y, z [m]
  double radius = 0.0;                             // sphere, capsule [m]
  double length = 0.0;  // capsule: length of the cylinder between the caps, along z [m]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      // centre, in the link frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // axes in the link frame
  double friction = 1.0;                                   // sliding friction coefficient
};

// MuJoCo sensors written at a site, named after it (sensordata by mj_name2id(mjOBJ_SENSOR)):
//   kForceTorque  "<site>_force", "<site>_torque": the wrench the parent body exerts on
//                 the site's body, about the site, in site axes (MuJoCo force/torque);
//                 put the site on a welded link to read across that fixed joint
//   kImu          "<site>_quat" (framequat, w x y z), "<site>_gyro" (site axes),
//                 "<site>_accelerometer" (proper acceleration, site axes: +g up at rest)
enum class SiteSensor { kNone, kForceTorque, kImu };

// A named point on a frame (MJCF <site>), e.g. where an IMU or F/T sensor reads.
struct Site {
  std::string name;                                        // MJCF site name
  std::string frame;                                       // a frame of the model
  Eigen::Vector3d position = Eigen::Vector3d::Zero();      // in the frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // in the frame
  SiteSensor sensor = SiteSensor::kNone;
};

struct Ground {
  bool enabled = false;  // a plane z = height, the only thing the robot's geoms touch
  double height = 0.0;
  double friction = 1.0;
};

// How a body's rotational inertia is written (kept for measurement; see README).
enum class InertiaForm {
  kDiagonal,  // principal moments + axes from Eigen's eigensolver ("diaginertia", "quat")
  kFull,      // the six components ("fullinertia"); MuJoCo diagonalises them itself
};

struct MjcfOptions {
  // Base: as the model (nullopt), or forced: true writes a free joint, false welds
  // the root body to the world at the origin (as a fixed-base wbi model).
  std::optional<bool> floating_base;
  std::string free_joint_name = "floating_base";

  // Per joint, in the model's joint order (ν order without the base); empty: all 0,
  // except armature, which is then the model's own (Model::joint_armature).
  // armature adds to the diagonal of M (rotor inertia reflected through the gear);
  // damping is viscous [N·m·s/rad]; frictionloss is dry (Coulomb) friction [N·m].
  std::vector<double> armature;
  std::vector<double> damping;
  std::vector<double> frictionloss;

  // Links lumped into a body by a fixed joint that MuJoCo should keep as bodies of
  // their own, welded to their parent (no joint), each with the links lumped below
  // it; e.g. the child link of an F/T sensor's fixed joint, so that a MuJoCo
  // force/torque sensor at a site on it measures the wrench across that joint.
  // The dynamics are unchanged (M and h agree as without).
  std::vector<std::string> welded_links;

  std::vector<ContactGeometry> contacts;
  std::vector<Site> sites;
  Ground ground;

  Eigen::Vector3d gravity{0.0, 0.0, -9.81};
  double timestep = 0.001;  // [s]
  Integrator integrator = Integrator::euler;
  // Constraint and contact buffers (MuJoCo 2.2 allocates them at load time).
  int njmax = 1000;
  int nconmax = 200;

  InertiaForm inertia_form = InertiaForm::kDiagonal;
};

// The MJCF text. Throws std::invalid_argument naming the option and the joint /
// frame / body when an option does not fit the model (unknown frame, wrong vector
// size, negative value, duplicate name) or when MuJoCo would reject a body of the
// model: a moving body with a mass or a principal moment below 1e-15, or principal
// moments breaking A + B ≥ C (load the model with LoadOptions::repair_inertia).
std::string write_mjcf(const wbi::model::Model& model, const MjcfOptions& options = {});

}  // namespace wbi::mjcf
