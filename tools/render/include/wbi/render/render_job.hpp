// `wbi render`: a recording to an MP4 video or one PNG frame (README.md).
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "wbi/render/frame_renderer.hpp"
#include "wbi/render/pose_track.hpp"

namespace wbi::render {

struct RenderOptions {
  std::filesystem::path recording;
  std::filesystem::path output;  // .mp4, or the PNG with png_time
  // The robot config (contact geometry, ground); none: the URDF the
  // recording's description names, its <collision> boxes as feet.
  std::optional<std::filesystem::path> robot_config;
  PoseSource source = PoseSource::kGroundTruth;
  // Ground truth on the left, the estimator's state on the right (`source` unused).
  bool compare = false;
  std::string robot;  // "": the only robot with a pose stream
  double fps = 30.0;
  int width = 1280;
  int height = 720;
  std::string camera = "track";    // track | fixed | a camera of the model
  double start = 0.0;              // [s] of recorded time, from the first pose
  std::optional<double> end;       // [s]; none: the last pose
  double speed = 1.0;              // recorded seconds per second of video
  std::optional<double> png_time;  // one frame at this time, as PNG
  // none: kHigh for a PNG, kFast for a video (frame_renderer.hpp).
  std::optional<Quality> quality;
  std::filesystem::path mesh_path;  // see FrameOptions::mesh_path
};

struct RenderProgress {
  int frames_done = 0;
  int frames_total = 0;
};

struct RenderSummary {
  int frames = 0;
  double start = 0.0;   // [s] recorded time of the first frame
  double end = 0.0;     // [s] recorded time of the last frame
  double wall_s = 0.0;  // time taken
  std::string robot;
  std::string gl_renderer;
};

// Number of frames of a video of [start, end] at `fps` and `speed`: one per
// 1/fps of video, the first at `start`, none past `end`.
int frame_count(double start, double end, double fps, double speed);

// Checks the options (std::invalid_argument with one line naming the option),
// reads the recording, renders and writes. `progress` is called after each frame.
RenderSummary render(const RenderOptions& options,
                     const std::function<void(const RenderProgress&)>& progress = {});

}  // namespace wbi::render
