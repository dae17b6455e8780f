// RobotScene (robot_scene.hpp).
#include "robot_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <stdexcept>

#include <wbi/mjcf/mjcf.hpp>
#include <wbi/mujoco_sim/load_mjcf.hpp>
#include <wbi/mujoco_sim/robot_mjcf.hpp>

#include "urdf_meshes.hpp"

namespace wbi::render {

using Eigen::Vector3d;

namespace {

// Colours of the skeleton style (README.md, "What is drawn").
constexpr float kBone[4] = {0.78f, 0.80f, 0.84f, 1.0f};
constexpr float kJoint[4] = {0.95f, 0.55f, 0.15f, 1.0f};
constexpr float kFoot[4] = {0.20f, 0.45f, 0.85f, 1.0f};
constexpr float kCom[4] = {0.90f, 0.15f, 0.15f, 1.0f};
constexpr float kForce[4] = {0.15f, 0.75f, 0.30f, 1.0f};

// The floor, sky and light: MJCF elements added to robot_mjcf's text.
// High quality: 4× multisampling and MuJoCo's default tessellation (28 slices,
// 16 stacks); fast: one sample per pixel and 12 × 6, which llvmpipe draws in
// about 30 % less time (README.md, "Speed").
std::string scenery(int width, int height, bool high_quality) {
  return "  <visual>\n"
         "    <global offwidth=\"" +
         std::to_string(width) + "\" offheight=\"" + std::to_string(height) +
         "\"/>\n"
         "    <quality shadowsize=\"2048\" offsamples=\"" +
         std::to_string(high_quality ? 4 : 0) + "\" numslices=\"" +
         std::to_string(high_quality ? 28 : 12) + "\" numstacks=\"" +
         std::to_string(high_quality ? 16 : 6) +
         "\"/>\n"
         "    <headlight ambient=\"0.3 0.3 0.3\" diffuse=\"0.4 0.4 0.4\" specular=\"0.1 0.1 "
         "0.1\"/>\n"
         "  </visual>\n"
         "  <asset>\n"
         "    <texture name=\"wbi_render_sky\" type=\"skybox\" builtin=\"gradient\" rgb1=\"0.55 "
         "0.68 0.82\""
         " rgb2=\"0.95 0.97 1\" width=\"32\" height=\"512\"/>\n"
         "    <texture name=\"wbi_render_grid\" type=\"2d\" builtin=\"checker\" rgb1=\"0.93 0.93 "
         "0.94\""
         " rgb2=\"0.80 0.82 0.85\" width=\"256\" height=\"256\" mark=\"edge\" markrgb=\"0.5 0.5 "
         "0.55\"/>\n"
         "    <material name=\"wbi_render_grid\" texture=\"wbi_render_grid\" texrepeat=\"4 4\""
         " texuniform=\"true\"/>\n"
         "  </asset>\n";
}

std::string floor_and_light(double height) {
  return "    <geom name=\"wbi_render_floor\" type=\"plane\" size=\"0 0 0.5\" pos=\"0 0 " +
         std::to_string(height) +
         "\" material=\"wbi_render_grid\" contype=\"0\" conaffinity=\"0\" group=\"1\"/>\n"
         "    <light name=\"wbi_render_sun\" directional=\"true\" castshadow=\"true\""
         " pos=\"1 1 4\" dir=\"-0.3 -0.2 -1\" diffuse=\"0.6 0.6 0.6\" specular=\"0.2 0.2 0.2\"/>\n";
}

// The MJCF text with the meshes read from their files, loaded from memory:
// mesh names need no escaping nor a lower-case extension.
mjModel* load_with_meshes(const std::string& xml, const std::vector<VfsMesh>& meshes,
                          const std::string& where) {
  std::vector<mujoco_sim::MemoryFile> files;
  for (const auto& mesh : meshes) {
    std::ifstream in(mesh.file, std::ios::binary);
    if (!in) {
      throw std::runtime_error("--mesh-path: cannot read " + mesh.file.string());
    }
    files.push_back({mesh.vfs_name, std::string((std::istreambuf_iterator<char>(in)),
                                                std::istreambuf_iterator<char>())});
  }
  return mujoco_sim::load_mjcf_from_memory(xml, files, where);
}

mjvGeom* next_geom(mjvScene* scene) {
  if (scene->ngeom >= scene->maxgeom) {
    return nullptr;  // full: MuJoCo's own rule is to drop what does not fit
  }
  return scene->geoms + scene->ngeom++;
}

void add_connector(mjvScene* scene, int type, double width, const Vector3d& a, const Vector3d& b,
                   const float rgba[4]) {
  if ((b - a).norm() < 1e-6) {
    return;  // no direction
  }
  mjvGeom* g = next_geom(scene);
  if (g == nullptr) {
    return;
  }
  mjv_initGeom(g, type, nullptr, nullptr, nullptr, rgba);
  mjv_makeConnector(g, type, width, a.x(), a.y(), a.z(), b.x(), b.y(), b.z());
  g->category = mjCAT_DECOR;
}

// size: as a model geom's (sphere: radius; cylinder: radius, half-length).
void add_shape(mjvScene* scene, int type, const Vector3d& size, const Vector3d& position,
               const float rgba[4]) {
  mjvGeom* g = next_geom(scene);
  if (g == nullptr) {
    return;
  }
  mjv_initGeom(g, type, size.data(), position.data(), nullptr, rgba);
  g->category = mjCAT_DECOR;
}

}  // namespace

RobotScene::RobotScene(const robot_config::RobotConfig& config,
                       const std::vector<std::string>& joint_names, int offscreen_width,
                       int offscreen_height, bool high_quality,
                       const std::filesystem::path& mesh_dir)
    : skeleton_(mesh_dir.empty()), ground_height_(config.ground.height) {
  const std::string where = "robot config (" + config.urdf + ")";
  const model::Model model = mujoco_sim::robot_model(config);
  const sim_models::SimPlan plan = sim_models::make_sim_plan(config, model, where);
  mujoco_sim::RobotMjcf written = mujoco_sim::robot_mjcf(config, model, plan);
  written.options.ground.enabled = false;  // the floor below replaces it
  std::string xml = mjcf::write_mjcf(model, written.options);
  const auto world = xml.find("  <worldbody>\n");
  if (world == std::string::npos) {
    throw std::logic_error("RobotScene: no <worldbody> in the written MJCF");
  }
  xml.insert(world + std::strlen("  <worldbody>\n"), floor_and_light(config.ground.height));
  xml.insert(world, scenery(offscreen_width, offscreen_height, high_quality));
  std::vector<VfsMesh> vfs_meshes;
  if (!mesh_dir.empty()) {
    // The meshes go into the MuJoCo bodies their links were lumped into: load
    // once without them to learn those bodies' names.
    const auto visuals = urdf_visual_meshes(config.urdf, mesh_dir);
    mjModel* plain = mujoco_sim::load_mjcf_from_memory(xml, {}, where);
    try {
      xml = add_visual_meshes(std::move(xml), visuals, model, plain);
    } catch (...) {
      mj_deleteModel(plain);
      throw;
    }
    mj_deleteModel(plain);
    for (std::size_t k = 0; k < visuals.size(); ++k) {
      vfs_meshes.push_back({visual_mesh_file_name(k), visuals[k].file});
    }
  }
  m_ = load_with_meshes(xml, vfs_meshes, where);
  d_ = mj_makeData(m_);

  for (const auto& name : joint_names) {
    const int id = mj_name2id(m_, mjOBJ_JOINT, name.c_str());
    if (id < 0 || m_->jnt_type[id] == mjJNT_FREE) {
      throw std::runtime_error(where + ": the recording's joint '" + name +
                               "' is not a joint of the model");
    }
    qpos_of_.push_back(m_->jnt_qposadr[id]);
  }
  for (int g = 0; g < m_->ngeom; ++g) {
    const char* name = mj_id2name(m_, mjOBJ_GEOM, g);
    if (name != nullptr && std::strncmp(name, "wbi_contact_", 12) == 0) {
      std::copy(kFoot, kFoot + 4, m_->geom_rgba + 4 * g);
    }
  }
  leaf_.assign(static_cast<std::size_t>(m_->nbody), true);
  for (int b = 1; b < m_->nbody; ++b) {
    leaf_[static_cast<std::size_t>(m_->body_parentid[b])] = false;
  }
  for (std::size_t l = 0; l < plan.contact_links.size(); ++l) {
    const int site = mj_name2id(m_, mjOBJ_SITE, ("wbi_link_" + std::to_string(l)).c_str());
    contact_body_.push_back(site >= 0 ? m_->site_bodyid[site] : -1);
  }
  // A bone as thick as 1.2 % of the robot's size (0.5 m → 6 mm, 1.8 m → 22 mm); an
  // arrow as long as 0.6 × the robot's extent for its whole weight.
  bone_radius_ = std::clamp(0.012 * m_->stat.extent, 0.004, 0.03);
  double mass = 0.0;
  for (int b = 1; b < m_->nbody; ++b) {
    mass += m_->body_mass[b];
  }
  newton_length_ = mass > 0.0 ? 0.6 * m_->stat.extent / (mass * 9.81) : 0.001;
  mj_resetData(m_, d_);
  mj_kinematics(m_, d_);
  mj_comPos(m_, d_);
  mj_camlight(m_, d_);  // the light's pose: not part of mj_kinematics
}

RobotScene::~RobotScene() {
  mj_deleteData(d_);
  mj_deleteModel(m_);
}

void RobotScene::set_pose(const PoseFrame& frame) {
  if (m_->nq >= 7 && m_->njnt > 0 && m_->jnt_type[0] == mjJNT_FREE) {
    for (int i = 0; i < 3; ++i) {
      d_->qpos[i] = frame.base_position[i];
    }
    d_->qpos[3] = frame.base_orientation.w();
    d_->qpos[4] = frame.base_orientation.x();
    d_->qpos[5] = frame.base_orientation.y();
    d_->qpos[6] = frame.base_orientation.z();
  }
  for (std::size_t j = 0; j < qpos_of_.size() && j < frame.q.size(); ++j) {
    d_->qpos[qpos_of_[j]] = frame.q[j];
  }
  mj_kinematics(m_, d_);
  mj_comPos(m_, d_);
  mj_camlight(m_, d_);  // the light's pose: not part of mj_kinematics
}

Vector3d RobotScene::origin(int body) const { return Vector3d::Map(d_->xpos + 3 * body); }

Vector3d RobotScene::mass_centre(int body) const { return Vector3d::Map(d_->xipos + 3 * body); }

Vector3d RobotScene::com() const { return Vector3d::Map(d_->subtree_com + 3 * root_body()); }

void RobotScene::add_decorations(mjvScene* scene, const std::vector<Vector6d>& wrenches) const {
  const double r = bone_radius_;
  // Bones: body origin (the joint's origin) to each child body's origin; a
  // leaf body (hand, head) also to its centre of mass, so that it has a length.
  for (int b = 1; b < m_->nbody && skeleton_; ++b) {
    const int parent = m_->body_parentid[b];
    if (parent > 0) {
      add_connector(scene, mjGEOM_CAPSULE, r, origin(parent), origin(b), kBone);
    }
  }
  for (int b = 1; b < m_->nbody && skeleton_; ++b) {
    if (leaf_[static_cast<std::size_t>(b)]) {
      add_connector(scene, mjGEOM_CAPSULE, r, origin(b), mass_centre(b), kBone);
    }
    add_shape(scene, mjGEOM_SPHERE, Vector3d::Constant(1.5 * r), origin(b), kJoint);
  }
  // The CoM, a line down to the ground and a disc there.
  const Vector3d c = com();
  const Vector3d ground(c.x(), c.y(), ground_height_ + 0.002);
  add_shape(scene, mjGEOM_SPHERE, Vector3d::Constant(2.5 * r), c, kCom);
  add_connector(scene, mjGEOM_LINE, 2.0, c, ground, kCom);
  add_shape(scene, mjGEOM_CYLINDER, Vector3d(3.0 * r, 0.001, 0.0), ground, kCom);
  // Contact forces: an arrow per contact link along its force f, from the
  // centre of pressure c on the ground: where the wrench (f, τ) about the link
  // origin p has no horizontal moment, τ + (p − c) × f = (0, 0, ·) with c_z = ground.
  // Only when the recording's contact links are this config's: the simulator
  // sends one wrench per contact link of its own config, in its order.
  if (wrenches.size() != contact_body_.size()) {
    return;
  }
  for (std::size_t l = 0; l < wrenches.size(); ++l) {
    const Vector3d f = wrenches[l].head<3>();
    const Vector3d tau = wrenches[l].tail<3>();
    const int body = contact_body_[l];
    if (body < 0 || f.z() < 1.0) {
      continue;  // in the air (or a pull): no arrow
    }
    const Vector3d p = origin(body);
    const double dz = p.z() - ground_height_;  // (p − c)_z
    const Vector3d from(p.x() - (tau.y() + dz * f.x()) / f.z(),
                        p.y() - (dz * f.y() - tau.x()) / f.z(), ground_height_);
    add_connector(scene, mjGEOM_ARROW, 0.8 * r, from, from + newton_length_ * f, kForce);
  }
}

}  // namespace wbi::render
