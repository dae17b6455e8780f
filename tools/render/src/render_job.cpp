// render() (render_job.hpp).
#include "wbi/render/render_job.hpp"

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <stdexcept>

#include "wbi/render/image_output.hpp"
#include "wbi/robot_config/robot_config.hpp"

namespace wbi::render {

namespace {

void check(const RenderOptions& o) {
  if (!(o.fps > 0.0) || o.fps > 240.0) {
    throw std::invalid_argument("--fps: must be in (0, 240]");
  }
  if (!(o.speed > 0.0) || o.speed > 1000.0) {
    throw std::invalid_argument("--speed: must be in (0, 1000]");
  }
  if (!(o.start >= 0.0)) {
    throw std::invalid_argument("--start: must be >= 0");
  }
  if (o.end && !(*o.end > o.start)) {
    throw std::invalid_argument("--end: must be after --start");
  }
  if (o.png_time && !(*o.png_time >= 0.0)) {
    throw std::invalid_argument("--png: must be >= 0");
  }
  if (!o.mesh_path.empty() && !std::filesystem::is_directory(o.mesh_path)) {
    throw std::invalid_argument("--mesh-path: '" + o.mesh_path.string() + "' is not a directory");
  }
  if (o.output.empty()) {
    throw std::invalid_argument("-o: missing output file");
  }
  // What is written is what the name says: a PNG, or an MP4 (ffmpeg would
  // otherwise pick its format from the extension).
  const std::string extension = o.output.extension().string();
  if (o.png_time && extension != ".png") {
    throw std::invalid_argument("-o: '" + o.output.string() +
                                "' does not end in .png (--png writes a PNG)");
  }
  if (!o.png_time && extension != ".mp4") {
    throw std::invalid_argument("-o: '" + o.output.string() +
                                "' does not end in .mp4 (give --png T for one frame as PNG)");
  }
}

robot_config::RobotConfig config_for(const RenderOptions& o, const PoseTrack& track) {
  if (o.robot_config) {
    return robot_config::load_robot_config(o.robot_config->string());
  }
  if (track.urdf_path.empty() || !std::filesystem::exists(track.urdf_path)) {
    throw std::runtime_error(o.recording.string() + ": the description of '" + track.robot +
                             "' names no URDF found here ('" + track.urdf_path +
                             "'): give --robot-config");
  }
  robot_config::RobotConfig config;
  config.urdf = track.urdf_path;
  config.fixed_base = !track.floating_base;
  robot_config::complete_from_urdf(config);
  return config;
}

}  // namespace

int frame_count(double start, double end, double fps, double speed) {
  // A hair of tolerance so that an end that is a whole number of frames counts its own.
  return static_cast<int>(std::floor((end - start) * fps / speed + 1e-9)) + 1;
}

RenderSummary render(const RenderOptions& o,
                     const std::function<void(const RenderProgress&)>& progress) {
  check(o);
  const auto began = std::chrono::steady_clock::now();
  const PoseSource source = o.compare ? PoseSource::kGroundTruth : o.source;
  const PoseTrack track = read_pose_track(o.recording, source, o.robot);
  std::optional<PoseTrack> compare;
  if (o.compare) {
    // The state on the ground truth's time axis: both are source stamps of one robot.
    compare = read_pose_track(o.recording, PoseSource::kState, track.robot);
    const double offset = static_cast<double>(compare->first_stamp_ns - track.first_stamp_ns) / 1e9;
    for (auto& f : compare->frames) {
      f.t += offset;
    }
  }
  // Times are checked before rendering starts (EGL, the model).
  const double duration = track.duration();
  if (o.png_time) {
    if (*o.png_time > duration + 1e-9) {
      char text[160];
      std::snprintf(text, sizeof text, "--png: %.3f s is past the recording's end (%.3f s)",
                    *o.png_time, duration);
      throw std::invalid_argument(text);
    }
  } else if (o.start > duration) {
    char text[160];
    std::snprintf(text, sizeof text, "--start: %.3f s is past the recording's end (%.3f s)",
                  o.start, duration);
    throw std::invalid_argument(text);
  }
  const robot_config::RobotConfig config = config_for(o, track);
  FrameOptions frame_options;
  if (compare) {
    frame_options.compare = &*compare;
    frame_options.compare_label = track.robot + " state (estimator)";
  }
  frame_options.width = o.width;
  frame_options.height = o.height;
  frame_options.camera = o.camera;
  frame_options.mesh_path = o.mesh_path;
  frame_options.quality = o.quality.value_or(o.png_time ? Quality::kHigh : Quality::kFast);
  frame_options.label = track.robot + " " + pose_source_name(source);
  FrameRenderer renderer(track, config, frame_options);

  RenderSummary summary;
  summary.robot = track.robot;
  summary.gl_renderer = renderer.gl_renderer();
  if (o.png_time) {
    write_png(o.output, o.width, o.height, renderer.render(*o.png_time));
    summary.frames = 1;
    summary.start = summary.end = *o.png_time;
  } else {
    const double end = o.end ? std::min(*o.end, duration) : duration;
    const int frames = frame_count(o.start, end, o.fps, o.speed);
    // A dead ffmpeg is reported by write(), not by a SIGPIPE that ends the process.
    std::signal(SIGPIPE, SIG_IGN);
    Mp4Writer video(o.output, o.width, o.height, o.fps);
    for (int k = 0; k < frames; ++k) {
      const double t = o.start + k * o.speed / o.fps;
      video.write(renderer.render(t));
      if (progress) {
        progress({k + 1, frames});
      }
    }
    video.close();
    summary.frames = frames;
    summary.start = o.start;
    summary.end = o.start + (frames - 1) * o.speed / o.fps;
  }
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  return summary;
}

}  // namespace wbi::render
