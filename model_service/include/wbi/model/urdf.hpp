// Building a Model from a URDF (urdfdom).
//
// - Free-floating by default; fixed base with `fixed_base = true`, and
//   automatically when the root is a massless link named "world".
// - revolute, continuous and prismatic joints move; fixed joints are lumped:
//   the child's mass, CoM and rotational inertia are combined exactly with its
//   parent body. Every link stays addressable as a frame.
// - Links without <inertial> are massless. Mimic joints are independent joints
//   (MimicInfo records the relation). <gazebo>, <transmission>, <sensor> and
//   meshes are ignored. floating and planar joints are rejected.
// - Reduced model: `joints` lists the joints to keep, in the order wanted for q
//   and ν; every other movable joint is locked at `locked_positions[name]`
//   (default 0) and lumped like a fixed joint.
// - Armature (Model::joint_armature) by joint name from `armature`, default 0;
//   an entry for a joint locked in a reduced model is accepted and has no effect.
// - Joint order of a full model: depth-first from the root, children in the
//   order their joints appear in the file.
// Errors: std::runtime_error naming the file and what is wrong (missing or
// empty file, XML error with line, several roots or a loop, zero axis, negative
// mass, non-physical inertia (see LoadOptions::strict_inertia), unsupported joint type);
// std::invalid_argument for unknown joint names in the options, and for an
// armature on a fixed joint or that is negative or not finite.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "wbi/model/model.hpp"

namespace wbi::model {

struct LoadOptions {
  bool fixed_base = false;
  std::vector<std::string> joints;                 // empty: all movable joints
  std::map<std::string, double> locked_positions;  // for joints not kept
  std::map<std::string, double> armature;          // by joint name, ≥ 0 [kg·m² or kg]
  // Inertia checks. Always: mass ≥ 0, finite values, ixx, iyy, izz ≥ 0.
  // strict_inertia also requires a positive semi-definite inertia satisfying the
  // triangle inequality; it is off by default because published models break it
  // (GRiD's Atlas feet are indefinite, TALOS grippers break the triangle inequality).
  bool strict_inertia = false;
  // Replace every non-physical link inertia (indefinite, or breaking the triangle
  // inequality λ_i + λ_j ≥ λ_k of the principal moments) by the nearest physical one,
  // and list those links in Model::repaired_inertia_links. The principal axes are kept
  // and each negative second moment of mass σ_k = (Σλ)/2 − λ_k is raised to 1e-9 Σσ
  // (README "Inertia repair"). Off by default: the model is the URDF's, bit for bit.
  // MuJoCo rejects such inertias, so an MJCF export and the model it is compared or
  // run against must both be loaded with it (wbi model mjcf does). Takes precedence
  // over strict_inertia.
  bool repair_inertia = false;
};

Model load_urdf_file(const std::string& path, const LoadOptions& options = {});
Model load_urdf_string(const std::string& xml, const LoadOptions& options = {},
                       const std::string& source = "<string>");

}  // namespace wbi::model
