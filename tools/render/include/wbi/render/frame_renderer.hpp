// Frames of a recorded run as RGB images: a PoseTrack posed on its robot
// config's model, drawn by MuJoCo offscreen (OffscreenGl) with the time in a
// corner. What is drawn and how the camera moves: README.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "wbi/render/pose_track.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::render {

// kFast: one sample per pixel, no shadows (videos: ≥ 30 frames/s at 640×480 on
// llvmpipe); kHigh: 4× multisampling and shadows (pictures).
enum class Quality { kFast, kHigh };

struct FrameOptions {
  int width = 1280;
  int height = 720;
  // "track" (follows the robot's CoM), "fixed" (looks at where the CoM was at
  // the first frame drawn), or the name of a camera of the model.
  std::string camera = "track";
  Quality quality = Quality::kFast;
  // Not empty: the URDF's visual meshes (STL), `package://` resolved here,
  // drawn instead of the skeleton's bones (README.md, "Meshes").
  std::filesystem::path mesh_path;
  std::string label;  // drawn beside the time, e.g. "humanoid ground_truth"
  // With a second track (same robot, same time base): the image split in two,
  // `track` on the left and this one on the right, one camera for both (aimed
  // at the left robot's CoM), so that a difference of pose or place shows.
  const PoseTrack* compare = nullptr;
  std::string compare_label;
};

class FrameRenderer {
 public:
  // Makes the EGL context and MuJoCo's render context. Throws RenderUnavailable
  // (offscreen_gl.hpp) when rendering cannot start here, std::runtime_error for
  // a model that does not fit the track, std::invalid_argument for a bad size
  // or an unknown camera.
  FrameRenderer(const PoseTrack& track, const robot_config::RobotConfig& config,
                FrameOptions options);
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  // The frame at track time t: width × height × 3 bytes, RGB, top row first.
  // Valid until the next call.
  const std::vector<std::uint8_t>& render(double t);

  int width() const;
  int height() const;
  std::string gl_renderer() const;  // e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// "1280x720" → {1280, 720}. Throws std::invalid_argument naming the value when
// it is not WxH with even sides in 16…4096 (H.264 wants even sides).
std::pair<int, int> parse_size(const std::string& text);

}  // namespace wbi::render
