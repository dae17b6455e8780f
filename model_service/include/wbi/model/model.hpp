// The kinematic tree of a robot: bodies with spatial inertias, 1-DoF joints,
// frames. Built once (see urdf.hpp) and immutable afterwards; every algorithm
// takes it as `const Model&` and keeps its scratch space in `Data` (data.hpp).
//
// Indexing
//   bodies   0 … n_bodies−1, parent[i] < i; body 0 is the root (the base).
//            Body i ≥ 1 is moved by exactly one joint, "joint of body i".
//   joints   0 … n_joints−1 in the order of ν (the model's joint order).
//            joint_body[k] is the body it moves; body_joint[i] the inverse.
//   q  (nq)  floating base: (p_WB [3], quaternion w,x,y,z [4], joint positions [n])
//            fixed base:    (joint positions [n]); the root sits at the world origin.
//   ν  (nv)  floating base: (ṗ_B [3] world axes, ω_B [3] world axes, q̇ [n])
//            ("mixed" representation); fixed base: q̇ [n].
//   frames   every URDF link, at a fixed placement in one body.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "wbi/model/spatial.hpp"

namespace wbi::model {

enum class JointType {
  kRevolute,   // rotation about a unit axis of the joint frame (URDF revolute, continuous)
  kPrismatic,  // translation along a unit axis of the joint frame
};

// A <mimic> tag as read from the URDF. Policy: the mimic joint is an ordinary,
// independent joint of the model (the relation is kept here for information only).
struct MimicInfo {
  std::string joint;  // the joint it mimics, empty when none
  double multiplier = 1.0;
  double offset = 0.0;
};

struct Model {
  std::string name;           // <robot name>
  std::string source;         // file it was loaded from, or "<string>"
  bool floating_base = true;  // false: root fixed at the world origin
  int nq = 0;                 // size of q
  int nv = 0;                 // size of ν
  int n_joints = 0;           // movable joints in the model
  int n_bodies = 0;           // rigid bodies after lumping fixed joints
  int base_nv = 6;            // 6 when floating, else 0: index of the first joint in ν
  int base_nq = 7;            // 7 when floating, else 0: index of the first joint in q

  // ---- bodies (size n_bodies) ----
  std::vector<int> parent;                   // parent body, −1 for the root
  std::vector<std::string> body_name;        // the URDF link that starts the body
  std::vector<double> body_mass;             // lumped mass [kg]
  std::vector<Vector3d> body_com;            // lumped CoM in body axes [m]
  std::vector<Matrix3d> body_inertia_c;      // lumped rotational inertia about the CoM, body axes
  std::vector<SpatialInertia> body_inertia;  // same, as spatial inertia about the body origin
  std::vector<int> body_joint;               // joint index of body i (−1 for the root)
  std::vector<int> body_subtree_size;  // bodies in the subtree of i, which are i … i + size − 1
  bool joint_order_is_body_order =
      true;  // joint k moves body k + 1 (false for a reordered reduced model)

  // ---- joint of body i (size n_bodies, entry 0 unused) ----
  std::vector<Matrix3d> joint_R_PJ;  // rotation of the joint frame in the parent body frame (q = 0)
  std::vector<Vector3d> joint_p_PJ;  // origin of the joint frame in the parent body frame
  std::vector<JointType> body_joint_type;
  std::vector<Vector3d> body_joint_axis;  // unit axis in the joint frame (= body frame)
  // Derived at load time, for speed (joint.hpp): the axis as ±e_k (k = 0,1,2) when it
  // is a coordinate axis, else k = −1; whether R_PJ is the identity; q and ν indices.
  std::vector<int> body_joint_axis_index;
  std::vector<double> body_joint_axis_sign;
  std::vector<bool> joint_R_PJ_identity;
  std::vector<int> body_q_index;  // index in q of the joint of body i (−1 for the root)
  std::vector<int> body_v_index;  // index in ν of the joint of body i (−1 for the root)

  // ---- joints, in ν order (size n_joints) ----
  std::vector<std::string> joint_name;
  std::vector<int> joint_body;     // body moved by joint k
  std::vector<int> joint_q_index;  // index in q  (= base_nq + k)
  std::vector<int> joint_v_index;  // index in ν  (= base_nv + k)
  std::vector<JointType> joint_type;
  std::vector<bool> joint_continuous;  // URDF "continuous" (no position limits)
  std::vector<double> joint_lower;     // position limits [rad or m]; ±inf when none
  std::vector<double> joint_upper;
  std::vector<double> joint_velocity_limit;  // [rad/s or m/s]; +inf when none
  std::vector<double> joint_effort_limit;    // [N·m or N]; +inf when none
  std::vector<MimicInfo> joint_mimic;
  // Armature [kg·m² or kg]: the rotor inertia reflected through the gear ratio
  // (I_rotor · ratio²), set by LoadOptions::armature, default 0. Convention (MuJoCo's):
  // the rotor is pure extra inertia about the joint axis, so armature_k adds to M(k, k)
  // only — to the joint block of M (CRBA), to the joint's D = Sᵀ I^A S + armature (ABA)
  // and τ_k += armature_k q̈_k (RNEA). It has no velocity terms (h, C unchanged), does
  // not enter G, and is not part of the centroidal momentum (h_G, A_G are those of the
  // rigid bodies; the base rows of M do not see it). Kinetic energy is ½ νᵀ M ν with it.
  std::vector<double> joint_armature;

  // Joints of the URDF that are movable but locked in this (reduced) model.
  std::vector<std::string> locked_joint_name;
  std::vector<double> locked_joint_position;

  // ---- frames (size n_frames): one per URDF link ----
  std::vector<std::string> frame_name;
  std::vector<int> frame_body;       // body the frame is attached to
  std::vector<Matrix3d> frame_R_BF;  // rotation of the frame in its body frame
  std::vector<Vector3d> frame_p_BF;  // origin of the frame in its body frame

  double total_mass = 0.0;  // Σ body_mass

  int n_frames() const { return static_cast<int>(frame_name.size()); }

  // Index of the named joint / frame / body; throws std::invalid_argument naming it.
  int joint_id(const std::string& joint) const;
  int frame_id(const std::string& frame) const;
  int body_id(const std::string& body) const;
  bool has_joint(const std::string& joint) const;
  bool has_frame(const std::string& frame) const;

  // Links whose inertia was replaced by the nearest physical one at load time
  // (LoadOptions::repair_inertia), in tree order; empty otherwise.
  std::vector<std::string> repaired_inertia_links;

  // ---- per frame (size n_frames), for splitting a body again (MJCF export) ----
  std::vector<int> frame_parent;  // frame of the URDF parent link, −1 for the root link
  // The link's own inertia (zero when massless), about its body's origin in body axes;
  // the frames of body i sum to body_inertia[i] (up to rounding).
  std::vector<SpatialInertia> frame_inertia;
};

}  // namespace wbi::model
