// A robot config loaded into MuJoCo for drawing only: the MJCF of
// wbi::mujoco_sim::robot_mjcf (the bodies MuJoCo simulates, fixed joints
// lumped) with a floor, a sky and a light added, posed from recorded joint
// positions and base pose (kinematics, no dynamics), and the "skeleton" drawn
// over it: see README.md, "What is drawn".
#pragma once

#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "wbi/render/pose_track.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::render {

class RobotScene {
 public:
  // config: complete (load_robot_config or complete_from_urdf done);
  // joint_names: the recording's joint order; offscreen_*: MuJoCo's offscreen
  // buffer size; high_quality: 4× multisampling and finer spheres and capsules;
  // mesh_dir: draw the URDF's visual meshes found there instead of the bones. Throws
  // std::runtime_error naming a recorded joint the model does not have.
  RobotScene(const robot_config::RobotConfig& config, const std::vector<std::string>& joint_names,
             int offscreen_width, int offscreen_height, bool high_quality,
             const std::filesystem::path& mesh_dir = {});
  ~RobotScene();
  RobotScene(const RobotScene&) = delete;
  RobotScene& operator=(const RobotScene&) = delete;

  // Sets qpos from the frame and runs MuJoCo's kinematics and CoM.
  void set_pose(const PoseFrame& frame);

  const mjModel* model() const { return m_; }
  mjData* data() { return d_; }
  int root_body() const { return 1; }
  Eigen::Vector3d com() const;                  // whole robot, world
  Eigen::Vector3d origin(int body) const;       // body frame origin, world
  Eigen::Vector3d mass_centre(int body) const;  // body's centre of mass, world
  double ground_height() const { return ground_height_; }

  // Appends the skeleton (capsules between body origins, joint spheres), the
  // CoM with its ground projection and, when `wrenches` is not empty, one
  // arrow per contact link at its centre of pressure, to `scene`.
  void add_decorations(mjvScene* scene, const std::vector<Vector6d>& wrenches) const;

 private:
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  std::vector<int> qpos_of_;       // per recorded joint: its qpos address
  bool skeleton_ = true;           // bones and joint spheres (not with meshes)
  std::vector<bool> leaf_;         // per body: it has no child body
  std::vector<int> contact_body_;  // per contact link (the ground truth's order): its body
  double ground_height_ = 0.0;
  double bone_radius_ = 0.01;     // [m], from the model's size
  double newton_length_ = 0.001;  // arrow length per newton [m]
};

}  // namespace wbi::render
