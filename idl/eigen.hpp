// Wire messages to and from Eigen, in one place for every layer: 3D vectors,
// quaternions, poses, wrenches and the double sequences and arrays of the
// samples. Conventions (docs/conventions.md): quaternions are (w, x, y, z),
// wrenches and 6D vectors linear first, a pose is the frame in the world.
//
// Every function writes into the caller's object: none allocates, except that
// to_wire into a sequence grows it the first time (resize keeps its capacity).
// A size that does not match throws std::invalid_argument naming the field.
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <wbi/msg/common.h>

namespace wbi::msg {

using Vector6d = Eigen::Matrix<double, 6, 1>;
// A floating base's coordinates: position [m], then orientation (w, x, y, z).
using Vector7d = Eigen::Matrix<double, 7, 1>;

namespace detail {

[[noreturn]] inline void size_mismatch(const char* what, std::size_t size, Eigen::Index expected) {
  throw std::invalid_argument(std::string(what) + ": " + std::to_string(size) +
                              " values, expected " + std::to_string(expected));
}

}  // namespace detail

// ---- 3D vectors

inline Eigen::Vector3d to_eigen(const Vector3& v) { return {v.x(), v.y(), v.z()}; }

inline void to_wire(const Eigen::Ref<const Eigen::Vector3d>& v, Vector3& out) {
  out.x(v.x());
  out.y(v.y());
  out.z(v.z());
}

// ---- Quaternions, as they are: neither normalised nor sign-changed

inline Eigen::Quaterniond to_eigen(const Quaternion& q) {
  return Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
}

// As (w, x, y, z), the order of the whole-body interface's flat arrays.
inline Eigen::Vector4d to_wxyz(const Quaternion& q) { return {q.w(), q.x(), q.y(), q.z()}; }

inline void to_wire(const Eigen::Quaterniond& q, Quaternion& out) {
  out.w(q.w());
  out.x(q.x());
  out.y(q.y());
  out.z(q.z());
}

// From (w, x, y, z), the order of the robot backends' readings.
inline void to_wire_wxyz(const Eigen::Ref<const Eigen::Vector4d>& wxyz, Quaternion& out) {
  out.w(wxyz[0]);
  out.x(wxyz[1]);
  out.y(wxyz[2]);
  out.z(wxyz[3]);
}

// ---- Poses

// The orientation of a homogeneous transform's rotation block (Eigen's
// conversion from a rotation matrix; its sign is Eigen's choice).
inline Eigen::Quaterniond orientation_of(const Eigen::Matrix4d& H) {
  return Eigen::Quaterniond(Eigen::Matrix3d(H.topLeftCorner<3, 3>()));
}

// world_H_frame from a pose, the orientation normalised (a zero quaternion
// gives the identity rotation, a NaN one a NaN rotation).
inline void to_transform(const Pose& pose, Eigen::Matrix4d& H) {
  H.setIdentity();
  H.topLeftCorner<3, 3>() = to_eigen(pose.orientation()).normalized().toRotationMatrix();
  H.topRightCorner<3, 1>() = to_eigen(pose.position());
}

// The same as an isometry.
inline Eigen::Isometry3d to_isometry(const Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = to_eigen(pose.orientation()).normalized().toRotationMatrix();
  X.translation() = to_eigen(pose.position());
  return X;
}

// (x, y, z, w, qx, qy, qz) as the pose carries them: a floating-base model's
// first seven coordinates.
inline void to_coordinates(const Pose& pose, Eigen::Ref<Vector7d> out) {
  const auto& p = pose.position();
  const auto& o = pose.orientation();
  out << p.x(), p.y(), p.z(), o.w(), o.x(), o.y(), o.z();
}

// A pose from world_H_frame: its translation and orientation_of(H).
inline void to_wire(const Eigen::Matrix4d& H, Pose& out) {
  to_wire(Eigen::Vector3d(H.topRightCorner<3, 1>()), out.position());
  to_wire(orientation_of(H), out.orientation());
}

// A pose from a position and an orientation (w, x, y, z).
inline void to_wire(const Eigen::Ref<const Eigen::Vector3d>& position,
                    const Eigen::Ref<const Eigen::Vector4d>& wxyz, Pose& out) {
  to_wire(position, out.position());
  to_wire_wxyz(wxyz, out.orientation());
}

// ---- Wrenches: (force, torque), linear first

inline void to_eigen(const Wrench& w, Eigen::Ref<Vector6d> out) {
  out << w.force().x(), w.force().y(), w.force().z(), w.torque().x(), w.torque().y(),
      w.torque().z();
}

inline void to_wire(const Eigen::Ref<const Vector6d>& w, Wrench& out) {
  to_wire(w.head<3>(), out.force());
  to_wire(w.tail<3>(), out.torque());
}

// ---- Sequences (std::vector<double>) and fixed arrays of doubles

// Copies a sequence into out, which must have its size already.
inline void to_eigen(const std::vector<double>& values, Eigen::Ref<Eigen::VectorXd> out,
                     const char* what) {
  if (values.size() != static_cast<std::size_t>(out.size())) {
    detail::size_mismatch(what, values.size(), out.size());
  }
  out = Eigen::Map<const Eigen::VectorXd>(values.data(), out.size());
}

// A sequence seen as an Eigen vector, not copied: valid while `values` lives
// and keeps its size (a sample's joints read where the sample holds them).
inline Eigen::Map<const Eigen::VectorXd> view(const std::vector<double>& values) {
  return {values.data(), static_cast<Eigen::Index>(values.size())};
}

// Copies v into a sequence, resized to v's size (no allocation once it has it).
inline void to_wire(const Eigen::Ref<const Eigen::VectorXd>& v, std::vector<double>& out) {
  out.resize(static_cast<std::size_t>(v.size()));
  Eigen::Map<Eigen::VectorXd>(out.data(), v.size()) = v;
}

// A 6D array of a message (a base velocity or acceleration) and back.
inline Vector6d to_eigen(const std::array<double, 6>& values) {
  return Eigen::Map<const Vector6d>(values.data());
}

inline void to_wire(const Eigen::Ref<const Vector6d>& v, std::array<double, 6>& out) {
  Eigen::Map<Vector6d>(out.data()) = v;
}

}  // namespace wbi::msg
