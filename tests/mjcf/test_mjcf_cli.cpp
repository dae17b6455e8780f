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
  options.integrator = wbi::mjcf::Integrator::kRK4;
  EXPECT_EQ(read(file), wbi::mjcf::write_mjcf(wm::load_urdf_file(urdf, load), options));

  const Output stdout_only = run({"mjcf", urdf, "--fixed-base", "-o", "-"});
  EXPECT_EQ(stdout_only.out.rfind("<mujoco model=\"humanoid\">", 0), 0U);
  EXPECT_EQ(stdout_only.out.find("type=\"free\""), std::string::npos);
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
  EXPECT_EQ(message({"mjcf", (dir_ / "missing.urdf").string(), "-o", "-"}),
            "URDF '" + (dir_ / "missing.urdf").string() +
                "': cannot open the file (missing or unreadable)");
}

}  // namespace
