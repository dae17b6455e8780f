// The robot for Foxglove's 3D panel: one transform per URDF link (from its
// parent link, the root from "world"), computed from a joint configuration
// and base pose with the model library's forward kinematics, as a JSON
// foxglove.FrameTransforms message. Frame ids are the URDF's link names, so
// Foxglove's URDF layer (robot_description) places its meshes on them.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include <wbi/model/data.hpp>
#include <wbi/model/model.hpp>

namespace wbi::bridge {

class FrameTransforms {
 public:
  // joint_names: the robot's joint order (its description); each must be a
  // joint of the URDF (std::runtime_error naming the first that is not).
  FrameTransforms(const std::string& urdf_path, bool floating_base,
                  const std::vector<std::string>& joint_names);

  // q in the robot's joint order; the base pose is ignored for a fixed base.
  std::string message(std::uint64_t stamp_ns, std::span<const double> q,
                      const Eigen::Isometry3d& world_T_base);

  std::size_t link_count() const { return static_cast<std::size_t>(model_.n_frames()); }
  std::size_t joint_count() const { return model_joint_of_.size(); }

  static const std::string& schema_name();
  static const std::string& json_schema();

 private:
  model::Model model_;
  model::Data data_;
  std::vector<int> model_joint_of_;  // robot joint j → model joint index
  Eigen::VectorXd joints_;           // model joint order
  std::vector<Eigen::Matrix4d> world_H_frame_;
};

}  // namespace wbi::bridge
