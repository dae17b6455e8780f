// `wbi model mjcf` (cli/src/verbs/model.cpp) called in-process: the file it writes
// is write_mjcf's text for the model loaded with inertia repair, each repaired link
// is named on stderr, and bad input is one error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include <wbi/mjcf/mjcf.hpp>
#include <wbi/model/urdf.hpp>
#include <wbi/mujoco_sim/robot_mjcf.hpp>
#include <wbi/robot_config/robot_config.hpp>

#include "test_support.hpp"
#include "verb.hpp"

namespace wbi::cli {
int run_model(Args args);
}

namespace {

namespace wm = wbi::model;

struct Output {
  std::string out, err;
};

Output run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  std::streambuf* old_out = std::cout.rdbuf(out.rdbuf());
  std::streambuf* old_err = std::cerr.rdbuf(err.rdbuf());
  try {
    EXPECT_EQ(wbi::cli::run_model(args), 0);
  } catch (...) {
    std::cout.rdbuf(old_out);
    std::cerr.rdbuf(old_err);
    throw;
  }
  std::cout.rdbuf(old_out);
  std::cerr.rdbuf(old_err);
  return {out.str(), err.str()};
}

std::string read(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class MjcfCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() /
        ("wbi_test_mjcf_cli_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(MjcfCli, WritesTheLibrarysTextForTheModel) {
  const auto urdf = wbi::test::project_model("humanoid.urdf").string();
  const auto file = dir_ / "humanoid.xml";
  const Output o = run({"mjcf", urdf, "-o", file.string(), "--welded", "l_foot,r_foot",
                        "--timestep", "0.002", "--integrator", "rk4"});
  EXPECT_EQ(o.out.rfind("wrote " + file.string() + ": humanoid, ", 0), 0U) << o.out;
  EXPECT_EQ(o.err, "");
  wm::LoadOptions load;
  load.repair_inertia = true;
  wbi::mjcf::MjcfOptions options;
  options.welded_links = {"l_foot", "r_foot"};
  options.timestep = 0.002;
  options.integrator = wbi::Integrator::rk4;
  EXPECT_EQ(read(file), wbi::mjcf::write_mjcf(wm::load_urdf_file(urdf, load), options));

  const Output stdout_only = run({"mjcf", urdf, "--fixed-base", "-o", "-"});
  EXPECT_EQ(stdout_only.out.rfind("<mujoco model=\"humanoid\">", 0), 0U);
  EXPECT_EQ(stdout_only.out.find("type=\"free\""), std::string::npos);
}

// --robot-config: the text MujocoBackend loads for that config (its armature,
// contact boxes, IMU and F/T sites and sensors, timestep and integrator).
TEST_F(MjcfCli, WritesWhatTheMujocoEngineLoadsForARobotConfig) {
  const auto config_file = (wbi::test::source_dir() / "deploy/robots/humanoid.yaml").string();
  const auto urdf = wbi::test::project_model("humanoid.urdf").string();
  const auto file = dir_ / "humanoid.xml";
  const Output o = run({"mjcf", urdf, "--robot-config", config_file, "-o", file.string()});
  EXPECT_EQ(o.out.rfind("wrote " + file.string() + ": humanoid, ", 0), 0U) << o.out;
  const auto config = wbi::robot_config::load_robot_config(config_file);
  const wm::Model model = wbi::mujoco_sim::robot_model(config);
  const std::string xml = read(file);
  EXPECT_EQ(xml, wbi::mjcf::write_mjcf(
                     model, wbi::mujoco_sim::robot_mjcf(config, model, config_file).options));
  for (const char* item : {"wbi_contact_0", "wbi_imu_0_accelerometer", "wbi_ft_1_torque"}) {
    EXPECT_NE(xml.find(item), std::string::npos) << item;
  }
}

TEST_F(MjcfCli, NamesTheRepairedLinksOnStderr) {
  const auto shared = wbi::test::shared_models_dir();
  if (!shared) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  const Output o = run(
      {"mjcf", (*shared / "talos/talos_reduced.urdf").string(), "-o", (dir_ / "t.xml").string()});
  for (const char* link : {"gripper_left_motor_single_link", "gripper_right_motor_single_link"}) {
    EXPECT_NE(o.err.find(std::string("wbi model mjcf: link '") + link +
                         "': non-physical inertia replaced by the nearest physical one"),
              std::string::npos)
        << o.err;
  }
}

TEST_F(MjcfCli, BadInputIsOneError) {
  const auto urdf = wbi::test::project_model("arm7.urdf").string();
  auto message = [&](const std::vector<std::string>& args) -> std::string {
    try {
      run(args);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(message({"mjcf", urdf}), "missing -o FILE (-o - writes to standard output)");
  EXPECT_EQ(message({"mjcf", urdf, "-o", "-", "--welded", "nope"}),
            "MJCF: welded_links: unknown link 'nope'");
  EXPECT_EQ(message({"mjcf", urdf, "-o", "-", "--integrator", "leapfrog"}),
            "--integrator: unknown 'leapfrog' (euler, rk4 or implicit)");
  EXPECT_EQ(message({"mjcf", urdf, "-o", "-", "--timestep", "0"}), "--timestep must be > 0");
  EXPECT_EQ(message({"mjcf", urdf, "-o", (dir_ / "no" / "such" / "dir.xml").string()}),
            "cannot write '" + (dir_ / "no" / "such" / "dir.xml").string() + "'");
  const auto humanoid_config = (wbi::test::source_dir() / "deploy/robots/humanoid.yaml").string();
  EXPECT_EQ(message({"mjcf", urdf, "-o", "-", "--robot-config", humanoid_config})
                .rfind("URDF '" + urdf + "' is not the robot config's (", 0),
            0U);
  const auto humanoid = wbi::test::project_model("humanoid.urdf").string();
  EXPECT_EQ(message({"mjcf", humanoid, "-o", "-", "--robot-config", humanoid_config, "--joints",
                     "l_knee"}),
            "--joints: a robot config describes the whole robot (no reduced model)");
  {
    std::ofstream bad(dir_ / "bad.yaml");
    bad << "urdf: " << humanoid << "\njionts: {}\n";
  }
  EXPECT_NE(message({"mjcf", humanoid, "-o", "-", "--robot-config", (dir_ / "bad.yaml").string()})
                .find("bad.yaml:2: jionts: unknown key"),
            std::string::npos);
  EXPECT_EQ(message({"mjcf", (dir_ / "missing.urdf").string(), "-o", "-"}),
            "URDF '" + (dir_ / "missing.urdf").string() +
                "': cannot open the file (missing or unreadable)");
}

}  // namespace
