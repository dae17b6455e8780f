// Several controllers in one host (issue 53): deploy/balance_and_arms_one_host.yaml
// balances the humanoid on its legs and torso (its CoM reference chained in)
// while PD holds the arms, in one process, in lockstep; the same on iCub 3
// (deploy/icub3_balance_and_arms.yaml, MuJoCo, ../shared). The arms go to
// hold at t = 8 s and back at 12 s: their torque does not step (the blend),
// the legs balance on as in a run without the switches (CoM figures within
// 0.1 mm), and both controllers meet their bounds.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

double last_value(const std::string& out, const std::string& marker) {
  const auto at = out.rfind(marker);
  return at == std::string::npos ? std::nan("") : std::stod(out.substr(at + marker.size()));
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// The launch's output, run to its end in one process (lockstep: the figures
// of the four processes, to the digit).
std::string run(const fs::path& deploy) {
  wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                                 {"launch", deploy.string(), "--one-process", "--duration", "200"});
  const auto code = launch.wait(240s);
  EXPECT_EQ(code.value_or(-1), 0) << launch.output();
  return launch.output();
}

struct Robot {
  const char* deploy;
  bool shared;  // needs ../shared/models
  double arms_bound;
};

class BalanceAndArmsOneHost : public ::testing::TestWithParam<Robot> {};

TEST_P(BalanceAndArmsOneHost, ArmsToHoldAndBackWhileTheLegsBalanceOn) {
  if (GetParam().shared && !wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  const fs::path deploy = wbi::test::source_dir() / "deploy" / GetParam().deploy;
  // The same file without its two switches, its paths made absolute.
  std::stringstream text;
  text << std::ifstream(deploy).rdbuf();
  const std::string folder = deploy.parent_path().string() + "/";
  std::string plain = replaced(text.str(),
                               "          switch_at_s: [8.0, 12.0]\n"
                               "          switch_to: [hold, arms]\n"
                               "          switch_from: [arms, \"\"]\n",
                               "");
  ASSERT_NE(plain, text.str()) << "the switches are not where the test expects them";
  plain = replaced(replaced(plain, "config: robots/", "config: " + folder + "robots/"), "urdf: ../",
                   "urdf: " + folder + "../");
  const fs::path plain_file =
      wbi::test::binary_dir() / "tests" / ("no_switch_" + std::string(GetParam().deploy));
  std::ofstream(plain_file) << plain;

  const std::string switched = run(deploy);
  const std::string unswitched = run(plain_file);
  for (const char* line : {"switch: arms → hold at t = 8.000 s; torque step",
                           "switch: hold → arms, hold at t = 12.000 s"}) {
    EXPECT_NE(switched.find(line), std::string::npos) << line << "\n" << switched;
  }
  // The arms' torques continue across both switches (the blend): no step.
  std::size_t steps = 0;
  for (auto at = switched.find("the joints that changed hands 0.00 %"); at != std::string::npos;
       at = switched.find("the joints that changed hands 0.00 %", at + 1)) {
    ++steps;
  }
  EXPECT_EQ(steps, 2u) << switched;
  const double rms = last_value(switched, "com tracking rms: ");
  const double rms_plain = last_value(unswitched, "com tracking rms: ");
  std::printf("com tracking rms: %.6f m with the arms switched, %.6f m without\n", rms, rms_plain);
  EXPECT_NEAR(rms, rms_plain, 1e-4) << "the switches of the arms moved the balancing";
  EXPECT_LT(rms, 0.002) << switched;
  const double arms = last_value(switched, "final max joint error: ");
  std::printf("arms: final max joint error %.6f rad\n", arms);
  EXPECT_LT(arms, GetParam().arms_bound) << switched;
}

// Bounds: a few times the measured final errors (0.00038 rad on both: half an encoder count).
INSTANTIATE_TEST_SUITE_P(Robots, BalanceAndArmsOneHost,
                         ::testing::Values(Robot{"balance_and_arms_one_host.yaml", false, 0.002},
                                           Robot{"icub3_balance_and_arms.yaml", true, 0.002}));

}  // namespace
