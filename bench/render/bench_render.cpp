// Frames per second of `wbi render` at 640×480 and 1280×720 on this machine's
// software rasteriser (llvmpipe): drawing only, and drawing + H.264 encoding
// through ffmpeg as `wbi render -o run.mp4` does. The humanoid
// (deploy/robots/humanoid.yaml) swaying and bending its joints, a synthetic
// 10 s track at 1 kHz, so that the benchmark needs no recording. Issue #25's
// target: ≥ 30 frames/s at 640×480 rendered and encoded.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>

#include <unistd.h>

#include <wbi/render/frame_renderer.hpp>
#include <wbi/render/image_output.hpp>
#include <wbi/render/offscreen_gl.hpp>
#include <wbi/render/pose_track.hpp>
#include <wbi/robot_config/robot_config.hpp>

namespace {

using wbi::render::FrameOptions;
using wbi::render::FrameRenderer;
using wbi::render::Quality;

const wbi::robot_config::RobotConfig& humanoid() {
  static const auto config = wbi::robot_config::load_robot_config(std::string(WBI_SOURCE_DIR) +
                                                                  "/deploy/robots/humanoid.yaml");
  return config;
}

const wbi::render::PoseTrack& swaying_track() {
  static const wbi::render::PoseTrack track = [] {
    wbi::render::PoseTrack t;
    t.robot = "humanoid";
    for (const auto& [name, dynamics] : humanoid().joints) {
      t.joint_names.push_back(name);
    }
    for (int k = 0; k <= 10'000; ++k) {
      wbi::render::PoseFrame f;
      f.t = k * 1e-3;
      f.base_position = {0.0, 0.05 * std::sin(2 * M_PI * 0.2 * f.t), 0.5};
      for (std::size_t j = 0; j < t.joint_names.size(); ++j) {
        f.q.push_back(0.3 * std::sin(2 * M_PI * 0.5 * f.t + static_cast<double>(j)));
      }
      t.frames.push_back(std::move(f));
    }
    return t;
  }();
  return track;
}

bool skip_without_egl(benchmark::State& state) {
  try {
    const wbi::render::OffscreenGl gl;
    return false;
  } catch (const wbi::render::RenderUnavailable& e) {
    state.SkipWithError(e.what());
    return true;
  }
}

FrameOptions options(benchmark::State& state, Quality quality) {
  FrameOptions o;
  o.width = static_cast<int>(state.range(0));
  o.height = static_cast<int>(state.range(1));
  o.quality = quality;
  o.label = "humanoid ground_truth";
  return o;
}

// Drawing and reading back one frame (no encoding).
void render_only(benchmark::State& state, Quality quality) {
  if (skip_without_egl(state)) {
    return;
  }
  FrameRenderer renderer(swaying_track(), humanoid(), options(state, quality));
  double t = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(renderer.render(t).data());
    t = std::fmod(t + 1.0 / 30.0, 10.0);
  }
  state.counters["frames_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_Render(benchmark::State& state) { render_only(state, Quality::kFast); }
void BM_RenderHighQuality(benchmark::State& state) { render_only(state, Quality::kHigh); }

// `wbi render -o run.mp4` without reading a recording: a 5 s clip at 30
// frames/s (150 frames) drawn and piped to ffmpeg, ffmpeg started and waited
// for inside the timing.
void BM_RenderAndEncode(benchmark::State& state) {
  if (skip_without_egl(state)) {
    return;
  }
  if (wbi::render::find_ffmpeg().empty()) {
    state.SkipWithError("ffmpeg not found (Debian package ffmpeg)");
    return;
  }
  constexpr int kFrames = 150;
  const std::filesystem::path out = std::filesystem::temp_directory_path() /
                                    ("wbi_bench_render_" + std::to_string(::getpid()) + ".mp4");
  FrameRenderer renderer(swaying_track(), humanoid(), options(state, Quality::kFast));
  for (auto _ : state) {
    wbi::render::Mp4Writer video(out, renderer.width(), renderer.height(), 30.0);
    for (int k = 0; k < kFrames; ++k) {
      video.write(renderer.render(k / 30.0));
    }
    video.close();
  }
  state.counters["frames_per_s"] = benchmark::Counter(
      static_cast<double>(state.iterations() * kFrames), benchmark::Counter::kIsRate);
  std::filesystem::remove(out);
}

BENCHMARK(BM_Render)
    ->Args({640, 480})
    ->Args({1280, 720})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_RenderHighQuality)
    ->Args({640, 480})
    ->Args({1280, 720})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_RenderAndEncode)
    ->Args({640, 480})
    ->Args({1280, 720})
    ->Unit(benchmark::kSecond)
    ->Iterations(2)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
