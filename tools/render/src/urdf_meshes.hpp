// `--mesh-path DIR`: the URDF's <visual> meshes, added to the MJCF that
// RobotScene draws, in place of the skeleton's bones (README.md, "Meshes").
#pragma once

#include <mujoco/mujoco.h>

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "wbi/model/model.hpp"

namespace wbi::render {

struct VisualMesh {
  std::string link;
  std::filesystem::path file;  // resolved, exists
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d p_LV = Eigen::Vector3d::Zero();  // visual origin in the link frame
  Eigen::Quaterniond q_LV = Eigen::Quaterniond::Identity();
};

// Every <visual> mesh of the URDF, its file resolved: "package://PKG/REST" as
// DIR/PKG/REST, else DIR/REST; "file://PATH" as PATH; a relative name beside
// the URDF. Throws std::runtime_error with one line naming the link and the
// file when it is not found or not STL (the one format MuJoCo 2.2 reads here).
std::vector<VisualMesh> urdf_visual_meshes(const std::string& urdf_file,
                                           const std::filesystem::path& mesh_dir);

// The name under which mesh k is given to MuJoCo (its virtual file system):
// "wbi_render_mesh_<k>.stl".
std::string visual_mesh_file_name(std::size_t k);

// A file given to MuJoCo in memory under another name.
struct VfsMesh {
  std::string vfs_name;
  std::filesystem::path file;
};

// `xml` (write_mjcf's text for `model`) with one <mesh> asset (file
// visual_mesh_file_name(k)) and one <geom>
// per visual, each in the MuJoCo body its link was lumped into (`plain`: that
// XML loaded, for its body names). Geoms in group 2, colliding with nothing.
std::string add_visual_meshes(std::string xml, const std::vector<VisualMesh>& meshes,
                              const model::Model& model, const mjModel* plain);

}  // namespace wbi::render
