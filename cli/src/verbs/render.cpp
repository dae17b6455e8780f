// `wbi render RECORDING -o run.mp4 | --png T -o frame.png`: a recorded run drawn
// offscreen by MuJoCo. The work is in wbi::render (tools/render), built
// only with MuJoCo, EGL and libpng; without them this verb names what is missing.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "../options.hpp"
#include "../terminal.hpp"
#include "verbs.hpp"

#ifdef WBI_WITH_RENDER
#include <wbi/render/frame_renderer.hpp>
#include <wbi/render/render_job.hpp>
#endif

namespace wbi::cli {

namespace {

#ifdef WBI_WITH_RENDER
// "[#########...........]  45/300 frames  12.3 frames/s"
std::string bar(const render::RenderProgress& p, double frames_per_second) {
  constexpr int kWidth = 30;
  const int filled = p.frames_total > 0 ? kWidth * p.frames_done / p.frames_total : kWidth;
  char text[128];
  std::snprintf(text, sizeof text, "[%.*s%.*s] %d/%d frames  %.1f frames/s", filled,
                "##############################", kWidth - filled, "..............................",
                p.frames_done, p.frames_total, frames_per_second);
  return text;
}
#endif

}  // namespace

int run_render(Args args) {
  Options options(
      "wbi render RECORDING.mcap -o run.mp4 [options] | --png T -o frame.png",
      "Draws a recorded run: the robot posed per frame from its recorded pose stream\n"
      "(kinematics only) as a skeleton with its feet, CoM and contact forces, rendered\n"
      "offscreen by MuJoCo (EGL, no display) into an H.264 MP4 (through the ffmpeg\n"
      "program), or one frame at time T into a PNG. Times are seconds of recorded\n"
      "time from the first pose. tools/render/README.md.");
  options.positional("RECORDING", "the .mcap file (`wbi record`)");
  options.option("output", "FILE", "the .mp4 (or .png with --png) to write (also -o FILE)");
  options.option("png", "T", "write one frame at time T as PNG instead of a video");
  options.option("robot-config", "FILE",
                 "robot config (contact geometry, ground); default: the URDF the recording's "
                 "description names");
  options.option("robot", "NAME", "the robot, when the recording has several");
  options.option("source", "SOURCE", "pose stream: ground_truth or state", "ground_truth");
  options.flag("compare",
               "ground truth (left) and the estimator's state (right) side by side, one camera");
  options.option("fps", "N", "frames per second of video", "30");
  options.option("size", "WxH", "image size in pixels", "1280x720");
  options.option("camera", "CAMERA", "track (follows the CoM), fixed, or a camera of the model",
                 "track");
  options.option("quality", "Q",
                 "fast (no shadows, 1 sample per pixel) or high (shadows, 4x multisampling); "
                 "default: high for --png, fast for a video");
  options.option("mesh-path", "DIR",
                 "draw the URDF's visual meshes (binary STL), package:// resolved in DIR, "
                 "instead of the skeleton's bones");
  options.option("start", "S", "first recorded second drawn", "0");
  options.option("end", "S", "last recorded second drawn (default: the end)");
  options.option("speed", "X", "recorded seconds per second of video", "1");
  options.example("wbi render run.mcap -o run.mp4",
                  "a recording of the demo (wbi record -o run.mcap --all) as a video");
  options.example("wbi render run.mcap --png 2 -o frame.png", "the frame at 2 s");
  options.example("wbi render run.mcap --compare -o compare.mp4",
                  "the ground truth beside the estimator's state");
  if (!options.parse(args)) {
    return kExitOk;
  }
  if (!options.has("output")) {
    throw UsageError("missing -o FILE (.mp4, or .png with --png)");
  }
#ifndef WBI_WITH_RENDER
  std::cerr << "wbi render: not available in this build: " WBI_RENDER_UNAVAILABLE "\n";
  return kExitError;
#else
  render::RenderOptions o;
  o.recording = options.get("RECORDING");
  o.output = options.get("output");
  if (const auto file = options.get_optional("robot-config")) {
    o.robot_config = *file;
  }
  o.robot = options.get_optional("robot").value_or("");
  o.source = render::pose_source_from_name(options.get("source"));
  o.compare = options.has("compare");
  o.fps = options.get_double("fps");
  std::tie(o.width, o.height) = render::parse_size(options.get("size"));
  o.camera = options.get("camera");
  if (const auto quality = options.get_optional("quality")) {
    if (*quality != "fast" && *quality != "high") {
      throw UsageError("--quality: '" + *quality + "' is not fast or high");
    }
    o.quality = *quality == "high" ? render::Quality::kHigh : render::Quality::kFast;
  }
  o.mesh_path = options.get_optional("mesh-path").value_or("");
  o.start = options.get_double("start");
  if (options.has("end")) {
    o.end = options.get_double("end");
  }
  o.speed = options.get_double("speed");
  if (options.has("png")) {
    o.png_time = options.get_double("png");
  }
  ProgressLine line;
  const auto began = std::chrono::steady_clock::now();
  int shown_tenth = -1;
  const auto summary = render::render(o, [&](const render::RenderProgress& p) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
    const int tenth = p.frames_total > 0 ? 10 * p.frames_done / p.frames_total : 10;
    // In place on a terminal; one line per tenth into a pipe or a log.
    if (line.on_terminal() || tenth != shown_tenth) {
      line.show(bar(p, elapsed > 0 ? p.frames_done / elapsed : 0.0));
      shown_tenth = tenth;
    }
  });
  line.finish();
  std::printf("%s: %d frame%s of %s, t = %.3f to %.3f s, %.1f s (%s)\n", o.output.string().c_str(),
              summary.frames, summary.frames == 1 ? "" : "s", summary.robot.c_str(), summary.start,
              summary.end, summary.wall_s, summary.gl_renderer.c_str());
  return kExitOk;
#endif
}

}  // namespace wbi::cli
