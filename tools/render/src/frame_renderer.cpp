// FrameRenderer (frame_renderer.hpp).
#include "wbi/render/frame_renderer.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "robot_scene.hpp"
#include "wbi/render/offscreen_gl.hpp"

namespace wbi::render {

namespace {

constexpr int kMaxSceneGeoms = 4000;
constexpr double kAzimuth = 150.0;    // [deg] in front of the robot (x forward), a bit to its left
constexpr double kElevation = -20.0;  // [deg] slightly from above

}  // namespace

std::pair<int, int> parse_size(const std::string& text) {
  int w = 0;
  int h = 0;
  char x = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') ||
      w < 16 || h < 16 || w > 4096 || h > 4096 || w % 2 != 0 || h % 2 != 0) {
    throw std::invalid_argument("--size: '" + text +
                                "' is not WIDTHxHEIGHT with even sides from 16 to 4096");
  }
  return {w, h};
}

struct FrameRenderer::Impl {
  const PoseTrack& track;
  FrameOptions options;
  OffscreenGl gl;  // before anything MuJoCo draws with
  RobotScene scene;
  std::unique_ptr<RobotScene> compare_scene;  // with options.compare
  mjvOption vopt;
  mjvCamera camera;
  mjvScene scn;
  mjvScene compare_scn;
  mjrContext con;
  mjvPerturb pert;
  bool track_com = false;
  bool camera_placed = false;
  double lookat_offset = 0.0;  // [m] added to the CoM's z
  std::vector<std::uint8_t> flipped;
  std::vector<std::uint8_t> rgb;

  Impl(const PoseTrack& t, const robot_config::RobotConfig& config, FrameOptions o)
      : track(t),
        options(std::move(o)),
        scene(config, t.joint_names, options.width, options.height,
              options.quality == Quality::kHigh, options.mesh_path) {
    mjv_defaultOption(&vopt);
    for (int g = 0; g < mjNGROUP; ++g) {
      vopt.sitegroup[g] = 0;  // the MJCF's sensor and link sites are not for show
    }
    mjv_defaultCamera(&camera);
    mjv_defaultPerturb(&pert);
    mjv_defaultScene(&scn);
    mjr_defaultContext(&con);
    const mjModel* m = scene.model();
    camera.azimuth = kAzimuth;
    camera.elevation = kElevation;
    if (options.camera == "track" || options.camera == "fixed") {
      // Both aim with a free camera placed at the first frame drawn; "track"
      // then follows the CoM.
      camera.type = mjCAMERA_FREE;
      track_com = options.camera == "track";
    } else {
      const int id = mj_name2id(m, mjOBJ_CAMERA, options.camera.c_str());
      if (id < 0) {
        std::string known;
        for (int c = 0; c < m->ncam; ++c) {
          known += std::string(", ") + mj_id2name(m, mjOBJ_CAMERA, c);
        }
        throw std::invalid_argument("--camera: unknown camera '" + options.camera +
                                    "' (track, fixed" + known + ")");
      }
      camera.type = mjCAMERA_FIXED;
      camera.fixedcamid = id;
    }
    // Software rasterising pays per sample and per pass: the fast look draws
    // one sample per pixel and no shadow pass (README.md, "Speed").
    const bool high = options.quality == Quality::kHigh;
    mjv_defaultScene(&compare_scn);
    mjv_makeScene(m, &scn, kMaxSceneGeoms);
    scn.flags[mjRND_SHADOW] = high ? 1 : 0;
    if (options.compare != nullptr) {
      compare_scene =
          std::make_unique<RobotScene>(config, options.compare->joint_names, options.width,
                                       options.height, high, options.mesh_path);
      mjv_makeScene(compare_scene->model(), &compare_scn, kMaxSceneGeoms);
      compare_scn.flags[mjRND_SHADOW] = scn.flags[mjRND_SHADOW];
    }
    mjr_makeContext(m, &con, options.height >= 600 ? mjFONTSCALE_150 : mjFONTSCALE_100);
    mjr_setBuffer(mjFB_OFFSCREEN, &con);
    if (con.currentBuffer != mjFB_OFFSCREEN || con.offWidth < options.width ||
        con.offHeight < options.height) {
      throw RenderUnavailable("MuJoCo's offscreen buffer did not start at " +
                              std::to_string(options.width) + "x" + std::to_string(options.height));
    }
    const auto n =
        static_cast<std::size_t>(options.width) * static_cast<std::size_t>(options.height) * 3;
    flipped.resize(n);
    rgb.resize(n);
  }

  // Looks at the CoM, raised or lowered to the middle of the robot's height at
  // the first frame (then kept: the view follows the CoM). The distance, set at
  // the first frame, shows the whole robot: MuJoCo's 45° field of view sees
  // 0.83 × the distance in height, so 1.8 × the robot's size fills ~2/3 of it.
  void aim_at_com() {
    const Eigen::Vector3d c = scene.com();
    if (!camera_placed) {
      double top = 0.0;     // highest body origin or centre of mass above the ground
      double spread = 0.0;  // farthest of them from the CoM, horizontally
      for (int b = 1; b < scene.model()->nbody; ++b) {
        for (const Eigen::Vector3d& p : {scene.origin(b), scene.mass_centre(b)}) {
          top = std::max(top, p.z() - scene.ground_height());
          spread = std::max(spread, (p - c).head<2>().norm());
        }
      }
      const double size = std::max({top, 2.0 * spread, 0.2});
      camera.distance = 1.8 * size;
      lookat_offset = scene.ground_height() + 0.5 * top - c.z();
      camera_placed = true;
    }
    camera.lookat[0] = c.x();
    camera.lookat[1] = c.y();
    camera.lookat[2] = c.z() + lookat_offset;
  }

  ~Impl() {
    mjr_freeContext(&con);
    mjv_freeScene(&compare_scn);
    mjv_freeScene(&scn);
  }

  const std::vector<std::uint8_t>& render(double t) {
    const PoseFrame& frame = track.at(t);
    scene.set_pose(frame);
    if (camera.type == mjCAMERA_FREE && (track_com || !camera_placed)) {
      aim_at_com();
    }
    char time[32];
    std::snprintf(time, sizeof time, "%.2f s", t);
    const mjrRect viewport{0, 0, options.width, options.height};
    mjrRect left = viewport;
    if (compare_scene) {
      left.width = options.width / 2;
      const mjrRect right{left.width, 0, options.width - left.width, options.height};
      const PoseFrame& other = options.compare->at(t);
      compare_scene->set_pose(other);
      mjv_updateScene(compare_scene->model(), compare_scene->data(), &vopt, &pert, &camera,
                      mjCAT_ALL, &compare_scn);
      compare_scene->add_decorations(&compare_scn, other.contact_wrenches);
      mjr_render(right, &compare_scn, &con);
      mjr_overlay(mjFONT_SHADOW, mjGRID_TOPLEFT, right, time, options.compare_label.c_str(), &con);
    }
    mjv_updateScene(scene.model(), scene.data(), &vopt, &pert, &camera, mjCAT_ALL, &scn);
    scene.add_decorations(&scn, frame.contact_wrenches);
    mjr_render(left, &scn, &con);
    mjr_overlay(mjFONT_SHADOW, mjGRID_TOPLEFT, left, time, options.label.c_str(), &con);
    mjr_readPixels(flipped.data(), nullptr, viewport, &con);
    // OpenGL's rows run bottom-up; images top-down.
    const auto row = static_cast<std::size_t>(options.width) * 3;
    for (int y = 0; y < options.height; ++y) {
      std::copy_n(
          flipped.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)), row,
          rgb.begin() +
              static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(options.height - 1 - y)));
    }
    return rgb;
  }
};

FrameRenderer::FrameRenderer(const PoseTrack& track, const robot_config::RobotConfig& config,
                             FrameOptions options)
    : impl_(std::make_unique<Impl>(track, config, std::move(options))) {}

FrameRenderer::~FrameRenderer() = default;

const std::vector<std::uint8_t>& FrameRenderer::render(double t) { return impl_->render(t); }

int FrameRenderer::width() const { return impl_->options.width; }
int FrameRenderer::height() const { return impl_->options.height; }
std::string FrameRenderer::gl_renderer() const { return impl_->gl.renderer(); }

}  // namespace wbi::render
