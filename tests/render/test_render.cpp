// `wbi render` as a user runs it, on a recording made as a user makes one:
// `wbi record` beside `wbi launch deploy/balance.yaml` (the own humanoid
// balancing, lockstep). The MP4 has the frame count and duration asked for
// (ffprobe); a PNG frame is not uniform, the same time gives the same image
// and another time moves the robot's pixels; bad inputs exit 1 with one line.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <unistd.h>

#include <wbi/mcap/writer.hpp>

#include "child_process.hpp"
#include "test_support.hpp"

#ifdef WBI_WITH_RENDER
#include <png.h>

#include <wbi/render/frame_renderer.hpp>
#include <wbi/render/offscreen_gl.hpp>
#include <wbi/render/pose_track.hpp>
#include <wbi/render/render_job.hpp>
#endif

namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

fs::path wbi_program() { return wbi::test::binary_dir() / "bin" / "wbi"; }

struct CliRun {
  int code;
  std::string output;
};

CliRun run_wbi(const std::vector<std::string>& args, std::chrono::milliseconds timeout = 120s) {
  wbi::test::ChildProcess process(wbi_program(), args);
  const auto code = process.wait(timeout);
  return {code.value_or(-1), process.output()};
}

// A fresh directory per test program run.
fs::path work_dir() {
  static const fs::path dir = [] {
    const fs::path d =
        fs::temp_directory_path() / ("wbi_test_render_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// Removes work_dir() after the last test.
class RemoveWorkDir : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(work_dir()); }
};
const auto* const kRemoveWorkDir = ::testing::AddGlobalTestEnvironment(new RemoveWorkDir);

// A file that is not MCAP.
fs::path not_mcap() {
  const fs::path file = work_dir() / "not_mcap.mcap";
  std::ofstream(file) << "this is not an MCAP file\n";
  return file;
}

// One line on stderr/stdout naming `what`, exit 1.
void expect_one_line_error(const CliRun& run, const std::string& what) {
  EXPECT_EQ(run.code, 1) << run.output;
  ASSERT_FALSE(run.output.empty());
  EXPECT_EQ(run.output.find('\n'), run.output.size() - 1) << "more than one line:\n" << run.output;
  EXPECT_EQ(run.output.rfind("wbi render: ", 0), 0u) << run.output;
  EXPECT_NE(run.output.find(what), std::string::npos) << "expected '" << what << "' in\n"
                                                      << run.output;
}

#ifndef WBI_WITH_RENDER

TEST(Render, NamesWhatIsMissingWhenNotBuilt) {
  const CliRun run =
      run_wbi({"render", not_mcap().string(), "-o", (work_dir() / "x.mp4").string()});
  expect_one_line_error(run, "not available in this build: ");
}

#else

bool has_program(const char* name) {
  const std::string command = std::string("command -v ") + name + " > /dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

fs::path mcap_without_poses() {
  const fs::path file = work_dir() / "no_poses.mcap";
  wbi::mcap::Writer writer(file.string(), {});
  const auto schema = writer.add_schema("wbi::msg::SensorSample", "struct SensorSample {};");
  const auto channel = writer.add_channel(schema, "wbi/humanoid/sensors", "cdr", {});
  const std::vector<std::uint8_t> bytes{0, 1, 0, 0};
  writer.write(channel, 0, 1'000'000'000u, 1'000'000'000u, bytes);
  writer.close();
  return file;
}

// What of Mesa's EGL is not installed (the reason to skip), or "" when it is:
// its EGL vendor library (libegl-mesa0) and, beside it, the software
// rasteriser the surfaceless platform draws with (swrast_dri.so,
// libgl1-mesa-dri). Found here, not by OffscreenGl: once they are installed,
// OffscreenGl failing to start is this project's failure, not a skip.
std::string mesa_egl_missing() {
  void* mesa = ::dlopen("libEGL_mesa.so.0", RTLD_LAZY | RTLD_LOCAL);
  if (mesa == nullptr) {
    return "Mesa's EGL is not installed (libEGL_mesa.so.0: Debian package libegl-mesa0)";
  }
  char directory[4096] = {};
  const bool found = ::dlinfo(mesa, RTLD_DI_ORIGIN, directory) == 0;
  ::dlclose(mesa);
  if (!found || !fs::exists(fs::path(directory) / "dri" / "swrast_dri.so")) {
    return std::string("Mesa's software rasteriser is not installed (") + directory +
           "/dri/swrast_dri.so: Debian package libgl1-mesa-dri)";
  }
  return "";
}

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;
};

Image read_png(const fs::path& file) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  Image out;
  if (png_image_begin_read_from_file(&image, file.c_str()) == 0) {
    ADD_FAILURE() << file << ": not a PNG: " << image.message;
    return out;
  }
  image.format = PNG_FORMAT_RGB;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr) == 0) {
    ADD_FAILURE() << file << ": " << image.message;
  }
  return out;
}

// The 2 s recording, made once for every test of this program.
class RecordedRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!(skip_ = mesa_egl_missing()).empty()) {
      return;
    }
    try {
      const wbi::render::OffscreenGl gl;
    } catch (const wbi::render::RenderUnavailable& e) {
      gl_failure_ =
          std::string("Mesa's EGL is installed, yet OffscreenGl did not start: ") + e.what();
      return;
    }
    recording_ = work_dir() / "balance.mcap";
    wbi::test::ChildProcess recorder(
        wbi_program(),
        {"record", "-o", recording_.string(), "wbi/humanoid/(description|ground_truth|state)"});
    ASSERT_TRUE(recorder.wait_for_output("recording", 30s)) << recorder.output();
    // Lockstep runs as fast as the machine allows: 8 s of wall time, of which
    // 1–2 s start the processes, give 4–6 s of robot time on this 2-core
    // machine under load, so at least the 2 s the tests need.
    wbi::test::ChildProcess launch(
        wbi_program(), {"launch", (wbi::test::source_dir() / "deploy" / "balance.yaml").string(),
                        "--duration", "8"});
    const auto code = launch.wait(60s);
    ASSERT_TRUE(code.has_value()) << launch.output();
    ASSERT_EQ(*code, 0) << launch.output();
    ASSERT_EQ(recorder.stop(2 /* SIGINT: the file gets its summary */, 10s), 0)
        << recorder.output();
    const auto track =
        wbi::render::read_pose_track(recording_, wbi::render::PoseSource::kGroundTruth);
    duration_ = track.duration();
  }

  void SetUp() override {
    if (!skip_.empty()) {
      GTEST_SKIP() << skip_;
    }
    ASSERT_EQ(gl_failure_, "");
    ASSERT_GE(duration_, 2.0) << "the recorded run is shorter than 2 s";
  }

  static std::vector<std::string> render_args(const fs::path& out) {
    return {"render",
            recording_.string(),
            "-o",
            out.string(),
            "--robot-config",
            (wbi::test::source_dir() / "deploy" / "robots" / "humanoid.yaml").string()};
  }

  static inline std::string skip_;
  static inline std::string gl_failure_;
  static inline fs::path recording_;
  static inline double duration_ = 0.0;
};

TEST_F(RecordedRun, Mp4HasTheFrameCountAndDurationAskedFor) {
  if (!has_program("ffmpeg") || !has_program("ffprobe")) {
    GTEST_SKIP() << "ffmpeg and ffprobe not found (Debian package ffmpeg)";
  }
  struct Case {
    std::vector<std::string> extra;
    int frames;
    double seconds;
  };
  // 2 s at 30 frames/s: frames at 0, 1/30, …, 2 s; at speed 2 and 10 frames/s:
  // 0, 0.2, …, 2 s of robot time in 1.1 s of video.
  const std::vector<Case> cases{
      {{"--end", "2", "--size", "320x240"}, 61, 61.0 / 30.0},
      {{"--end", "2", "--size", "320x240", "--fps", "10", "--speed", "2", "--camera", "fixed"},
       11,
       1.1},
  };
  for (const auto& c : cases) {
    const fs::path out = work_dir() / "run.mp4";
    auto args = render_args(out);
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const CliRun run = run_wbi(args);
    ASSERT_EQ(run.code, 0) << run.output;
    EXPECT_NE(run.output.find(std::to_string(c.frames) + " frames of humanoid"), std::string::npos)
        << run.output;
    const fs::path probe = work_dir() / "probe.txt";
    const std::string command =
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=codec_name,width,height,nb_read_frames,duration -of default=noprint_wrappers=1 '" +
        out.string() + "' > '" + probe.string() + "'";
    ASSERT_EQ(std::system(command.c_str()), 0);
    std::ifstream in(probe);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("codec_name=h264\n"), std::string::npos) << text;
    EXPECT_NE(text.find("width=320\n"), std::string::npos) << text;
    EXPECT_NE(text.find("height=240\n"), std::string::npos) << text;
    EXPECT_NE(text.find("nb_read_frames=" + std::to_string(c.frames) + "\n"), std::string::npos)
        << text;
    const auto at = text.find("duration=");
    ASSERT_NE(at, std::string::npos) << text;
    EXPECT_NEAR(std::stod(text.substr(at + 9)), c.seconds, 1e-3) << text;
  }
}

TEST_F(RecordedRun, PngIsNotUniformAndTheRobotMovesBetweenTimes) {
  auto png = [&](const std::string& time, const std::string& name) {
    const fs::path out = work_dir() / name;
    auto args = render_args(out);
    args.insert(args.end(), {"--png", time, "--size", "320x240", "--camera", "fixed"});
    const CliRun run = run_wbi(args);
    EXPECT_EQ(run.code, 0) << run.output;
    return read_png(out);
  };
  const Image a = png("0.5", "a.png");
  const Image again = png("0.5", "a_again.png");
  const Image b = png("2", "b.png");
  ASSERT_EQ(a.width, 320);
  ASSERT_EQ(a.height, 240);
  ASSERT_EQ(b.rgb.size(), a.rgb.size());
  std::set<std::uint32_t> colours;
  for (std::size_t i = 0; i + 2 < a.rgb.size(); i += 3) {
    colours.insert(static_cast<std::uint32_t>(a.rgb[i]) << 16 | a.rgb[i + 1] << 8 | a.rgb[i + 2]);
  }
  EXPECT_GT(colours.size(), 50u) << "a uniform picture";
  EXPECT_EQ(a.rgb, again.rgb) << "the same time drew two different pictures";
  // Below the time overlay (the top rows), the robot's pixels: the CoM swings
  // by ~5 cm between 0.5 s (settling) and 2 s (the sinusoid at 0.95 of its amplitude).
  const std::size_t row = static_cast<std::size_t>(a.width) * 3;
  std::size_t changed = 0;
  for (std::size_t i = row * 40; i < a.rgb.size(); i += 3) {
    changed += a.rgb[i] != b.rgb[i] || a.rgb[i + 1] != b.rgb[i + 1] || a.rgb[i + 2] != b.rgb[i + 2];
  }
  EXPECT_GT(changed, 50u) << "the robot did not move between 0.5 s and 2 s";
}

TEST_F(RecordedRun, CompareDrawsGroundTruthAndStateSideBySide) {
  const fs::path out = work_dir() / "compare.png";
  auto args = render_args(out);
  args.insert(args.end(), {"--png", "1.5", "--size", "640x240", "--compare", "--camera", "fixed"});
  const CliRun run = run_wbi(args);
  ASSERT_EQ(run.code, 0) << run.output;
  const Image image = read_png(out);
  ASSERT_EQ(image.width, 640);
  ASSERT_EQ(image.height, 240);
  // Each half, below its overlay, holds a robot on the floor: many colours,
  // and the two halves are nearly the same picture (the estimate is close to the truth).
  std::set<std::uint32_t> left;
  std::set<std::uint32_t> right;
  std::size_t differ = 0;
  for (int y = 40; y < image.height; ++y) {
    for (int x = 0; x < 320; ++x) {
      const auto at = [&](int px) {
        const std::size_t i =
            3 * (static_cast<std::size_t>(y) * 640 + static_cast<std::size_t>(px));
        return static_cast<std::uint32_t>(image.rgb[i]) << 16 | image.rgb[i + 1] << 8 |
               image.rgb[i + 2];
      };
      left.insert(at(x));
      right.insert(at(x + 320));
      differ += at(x) != at(x + 320);
    }
  }
  EXPECT_GT(left.size(), 50u);
  EXPECT_GT(right.size(), 50u);
  EXPECT_LT(differ, 320u * 200u / 4) << "the estimate's robot is far from the truth's";
}

// A binary STL box (unit cube about the origin, 12 triangles).
void write_cube_stl(const fs::path& file) {
  const float v[8][3] = {{-0.5f, -0.5f, -0.5f}, {-0.5f, -0.5f, 0.5f}, {-0.5f, 0.5f, -0.5f},
                         {-0.5f, 0.5f, 0.5f},   {0.5f, -0.5f, -0.5f}, {0.5f, -0.5f, 0.5f},
                         {0.5f, 0.5f, -0.5f},   {0.5f, 0.5f, 0.5f}};
  const int faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                            {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  std::ofstream out(file, std::ios::binary);
  const std::string header(80, '\0');
  out.write(header.data(), 80);
  const std::uint32_t count = 12;
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (const auto& f : faces) {
    const float normal[3] = {0, 0, 0};
    out.write(reinterpret_cast<const char*>(normal), sizeof normal);
    for (int i : f) {
      out.write(reinterpret_cast<const char*>(v[i]), sizeof v[i]);
    }
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), 2);
  }
}

// The humanoid's URDF with box meshes on the chest, the root link and the left
// hand (a link lumped into the forearm's body by a fixed joint), and its robot
// config pointing at it. Returns the config.
fs::path humanoid_with_meshes(const std::string& mesh_file) {
  const fs::path dir = work_dir() / "meshes";
  fs::create_directories(dir / "testpkg");
  write_cube_stl(dir / "testpkg" / "box.stl");
  std::ifstream in(wbi::test::project_model("humanoid.urdf"));
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto visual = [&](const char* scale) {
    return "<visual><origin xyz=\"0 0 0.05\" rpy=\"0 0 0.3\"/><geometry><mesh filename=\"" +
           mesh_file + "\" scale=\"" + scale + "\"/></geometry></visual>";
  };
  auto add = [&](const std::string& from, const std::string& to) {
    const auto at = urdf.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    urdf.replace(at, from.size(), to);
  };
  add("<link name=\"chest\">", "<link name=\"chest\">" + visual("0.12 0.2 0.2"));
  add("<link name=\"root_link\">", "<link name=\"root_link\">" + visual("0.1 0.2 0.1"));
  add("<link name=\"l_hand\"/>", "<link name=\"l_hand\">" + visual("0.06 0.06 0.06") + "</link>");
  std::ofstream(dir / "humanoid_meshes.urdf") << urdf;
  std::ifstream config_in(wbi::test::source_dir() / "deploy" / "robots" / "humanoid.yaml");
  std::string config((std::istreambuf_iterator<char>(config_in)), std::istreambuf_iterator<char>());
  const std::string key = "urdf: ../../models/humanoid.urdf";
  const auto at = config.find(key);
  EXPECT_NE(at, std::string::npos);
  config.replace(at, key.size(), "urdf: " + (dir / "humanoid_meshes.urdf").string());
  std::ofstream(dir / "humanoid_meshes.yaml") << config;
  return dir / "humanoid_meshes.yaml";
}

TEST_F(RecordedRun, MeshPathDrawsTheUrdfMeshes) {
  const fs::path config = humanoid_with_meshes("package://testpkg/box.stl");
  auto png = [&](const std::vector<std::string>& extra, const std::string& name) {
    const fs::path out = work_dir() / name;
    std::vector<std::string> args{"render",         recording_.string(), "-o",        out.string(),
                                  "--robot-config", config.string(),     "--png",     "1",
                                  "--size",         "320x240",           "--quality", "fast"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun run = run_wbi(args);
    EXPECT_EQ(run.code, 0) << run.output;
    return read_png(out);
  };
  const Image skeleton = png({}, "skeleton.png");
  const Image meshes = png({"--mesh-path", (work_dir() / "meshes").string()}, "meshes.png");
  ASSERT_EQ(skeleton.rgb.size(), meshes.rgb.size());
  ASSERT_FALSE(skeleton.rgb.empty());
  // The chest's box alone covers thousands of pixels where the skeleton drew a few bones.
  std::size_t changed = 0;
  for (std::size_t i = 0; i + 2 < skeleton.rgb.size(); i += 3) {
    changed += skeleton.rgb[i] != meshes.rgb[i] || skeleton.rgb[i + 1] != meshes.rgb[i + 1] ||
               skeleton.rgb[i + 2] != meshes.rgb[i + 2];
  }
  EXPECT_GT(changed, 1000u);

  const fs::path missing = humanoid_with_meshes("package://testpkg/missing.stl");
  expect_one_line_error(
      run_wbi({"render", recording_.string(), "-o", (work_dir() / "m.png").string(), "--png", "1",
               "--robot-config", missing.string(), "--mesh-path",
               (work_dir() / "meshes").string()}),
      "package://testpkg/missing.stl not found");
  expect_one_line_error(
      run_wbi({"render", recording_.string(), "-o", (work_dir() / "m.png").string(), "--png", "1",
               "--mesh-path", (work_dir() / "nowhere").string()}),
      "--mesh-path: ");
}

TEST_F(RecordedRun, BadInputsExitOneWithOneLine) {
  const fs::path out = work_dir() / "bad.mp4";
  {
    auto args = render_args(out);
    args.insert(args.end(), {"--camera", "nowhere"});
    expect_one_line_error(run_wbi(args), "unknown camera 'nowhere'");
  }
  for (const char* size : {"640", "0x480", "641x480", "axb"}) {
    auto args = render_args(out);
    args.insert(args.end(), {"--size", size});
    expect_one_line_error(run_wbi(args), "--size: '" + std::string(size) + "'");
  }
  {
    auto args = render_args(work_dir() / "late.png");
    args.insert(args.end(), {"--png", "1000"});
    expect_one_line_error(run_wbi(args), "past the recording's end");
  }
  expect_one_line_error(run_wbi({"render", not_mcap().string(), "-o", out.string()}),
                        not_mcap().string());
  expect_one_line_error(run_wbi({"render", mcap_without_poses().string(), "-o", out.string()}),
                        "no ground_truth stream");
  expect_one_line_error(
      run_wbi({"render", (work_dir() / "missing.mcap").string(), "-o", out.string()}),
      "missing.mcap");
  expect_one_line_error(run_wbi({"render", recording_.string()}), "missing -o");
  expect_one_line_error(run_wbi({"render", recording_.string(), "-o", "run.png"}),
                        "does not end in .mp4");
  expect_one_line_error(run_wbi({"render", recording_.string(), "--png", "1", "-o", "frame.mp4"}),
                        "does not end in .png");
}

TEST(RenderParts, FrameCountAndSize) {
  EXPECT_EQ(wbi::render::frame_count(0.0, 2.0, 30.0, 1.0), 61);
  EXPECT_EQ(wbi::render::frame_count(0.0, 2.0, 10.0, 2.0), 11);
  EXPECT_EQ(wbi::render::frame_count(1.0, 1.0, 30.0, 1.0), 1);
  EXPECT_EQ(wbi::render::frame_count(0.0, 0.999, 1.0, 1.0), 1);
  EXPECT_EQ(wbi::render::parse_size("1280x720"), std::make_pair(1280, 720));
  EXPECT_THROW(wbi::render::parse_size("1280x721"), std::invalid_argument);
  EXPECT_THROW(wbi::render::parse_size("1280x720x1"), std::invalid_argument);
}

#endif

}  // namespace
