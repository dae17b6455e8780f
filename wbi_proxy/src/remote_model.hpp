// The Model element evaluated by the robot's model service (wbi/<robot>/model,
// request/reply): every operation is one ModelRequest with the options'
// model_timeout as deadline.
//
// Orders: the service's model has its own joint order (its description on
// wbi/<robot>/model/description). service_joint_[k] is the position there of
// controlled joint k; the service's other joints travel at their locked
// positions with zero velocity. generalized_[i] maps the interface's
// generalized coordinate i (6 base + dofs) to the service's, or -1 where the
// service has none (the base of a fixed-base model): those rows and columns
// come back zero, as with LocalModel.
//
// Frames: the service's description names no frames, so frame names come
// from a URDF readable here (the options' urdf, else the service's
// urdf_path); without one, frame_index() accepts any name and the service
// names an unknown frame in its error reply.
//
// The request and reply are members, filled in place: after a warm-up call of
// each operation no call allocates outside Fast DDS.
#pragma once

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include <wbi/msg/description.h>
#include <wbi/msg/model.h>
#include <wbi/dds/client.hpp>
#include <wbi/dds/subscriber.hpp>

#include "wbi/dds_interface_options.hpp"
#include "wbi/model.hpp"

namespace wbi::proxy {

class RemoteModel final : public wbi::Model {
 public:
  // Creates the DDS endpoints; discovery runs while the proxy waits for the robot.
  RemoteModel(dds::Participant& participant, const DdsInterfaceOptions& options);

  // Waits until the service's description has arrived and the client is
  // connected; returns what is still missing ("" when ready).
  std::string wait_ready(std::chrono::steady_clock::time_point deadline);

  // Maps the controlled joints to the service's order; joints of the service
  // outside that list are held at `locked` (0 when not listed). Throws Error
  // naming a controlled joint the service's model does not have.
  void bind(const IdList& controlled, const std::map<std::string, double>& locked);

  const std::string& service() const { return client_.service(); }

  int dofs() const override { return static_cast<int>(service_joint_.size()); }
  const IdList& joint_list() const override { return controlled_; }
  const IdList& frame_list() const override { return frames_; }
  int frame_index(const std::string& frame) const override;
  JointLimits joint_limits(int joint) const override;

  void frame_pose(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                  Transform& out) override;
  void jacobian(const ConstVectorRef& q, const Transform& world_H_base, int frame,
                MatrixRef J) override;
  void dj_nu(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
             const ConstVectorRef& base_velocity, int frame, VectorRef out) override;
  void mass_matrix(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef M) override;
  void bias_forces(const ConstVectorRef& q, const Transform& world_H_base, const ConstVectorRef& dq,
                   const ConstVectorRef& base_velocity, const Eigen::Vector3d& gravity,
                   VectorRef h) override;
  void gravity_forces(const ConstVectorRef& q, const Transform& world_H_base,
                      const Eigen::Vector3d& gravity, VectorRef g) override;
  void inverse_dynamics(const ConstVectorRef& q, const Transform& world_H_base,
                        const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                        const ConstVectorRef& ddq, const ConstVectorRef& base_acceleration,
                        const Eigen::Vector3d& gravity, VectorRef tau) override;
  void centroidal_momentum(const ConstVectorRef& q, const Transform& world_H_base,
                           const ConstVectorRef& dq, const ConstVectorRef& base_velocity,
                           VectorRef out) override;
  void centroidal_momentum_matrix(const ConstVectorRef& q, const Transform& world_H_base,
                                  MatrixRef A) override;
  void com(const ConstVectorRef& q, const Transform& world_H_base, Eigen::Vector3d& out) override;
  void com_jacobian(const ConstVectorRef& q, const Transform& world_H_base, MatrixRef J) override;

 private:
  // Request fields from the interface's arguments (controlled joints → service order).
  void set_position(const ConstVectorRef& q, const Transform& world_H_base);
  void set_velocity(const ConstVectorRef& dq, const ConstVectorRef& base_velocity);
  void set_gravity(const Eigen::Vector3d& gravity);
  // One round trip for one operation; returns its result, checked to be rows × cols.
  // `what` names the interface operation in errors.
  const msg::OperationResult& call(msg::ModelOperation operation, int frame, const char* what,
                                   std::uint32_t rows, std::uint32_t cols);
  // Service result (rows × service nv) → interface columns (rows × (6 + dofs)).
  void map_columns(const msg::OperationResult& result, MatrixRef to) const;
  void map_vector(const msg::OperationResult& result, VectorRef to) const;
  std::uint32_t service_nv() const { return static_cast<std::uint32_t>(service_nv_); }

  std::string robot_;
  std::chrono::milliseconds timeout_;
  std::string urdf_;  // for frame names; may be empty
  dds::Subscriber<msg::RobotDescription> description_;
  dds::Received<msg::RobotDescription> description_rx_;
  dds::Client<msg::ModelRequest, msg::ModelReply> client_;

  bool floating_base_ = false;
  int service_nv_ = 0;
  int base_nv_ = 0;                 // 6 for a floating base, 0 for a fixed one
  IdList controlled_;               // the controlled joints, as bound
  std::vector<int> service_joint_;  // [dofs] index of controlled joint k in the service's joints
  std::vector<int> generalized_;    // [6 + dofs] service generalized index, −1: none (zero)
  mutable IdList frames_;           // see the header comment
  bool frames_known_ = false;       // frames_ came from a URDF
  msg::ModelRequest request_;
  msg::ModelReply reply_;
};

}  // namespace wbi::proxy
