// Only the deploy file changes: the lockstep PD + gravity demo and the
// balancing demo run with the DART backend (`model_backend: dart` in the
// controller's parameters) and end where they end with the project's library.
// Lockstep makes each run deterministic. The backends agree to ~1e-12 per
// call; the arm's smooth run keeps that (1e-6 asserted), while the humanoid's
// stick-slip contacts amplify it over thousands of ticks (measured: 0.3 % of
// the rms), hence a relative tolerance there.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "backend_test_common.hpp"
#include "child_process.hpp"
#include "deploy_text.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
namespace fs = std::filesystem;

// deploy/<name> with its relative paths made absolute (it is written elsewhere)
// and `line` inserted after the controller's line `after`.
fs::path deploy_variant(const std::string& name, const std::string& after, const std::string& line,
                        const std::string& tag) {
  std::string text = wbi::test::deploy_text(name);
  const auto at = text.find(after);
  EXPECT_NE(at, std::string::npos) << after << " not in " << name;
  if (at != std::string::npos && !line.empty()) {
    text.insert(text.find('\n', at) + 1, line + "\n");
  }
  return wbi::test::write_test_file("backend_" + tag + "_" + name, text);
}

// Runs `wbi launch FILE --duration S` and returns the number in its summary
// line "<marker>: X ...".
double launch_summary(const fs::path& file, const std::string& marker, int duration_s) {
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", file.string(), "--duration", std::to_string(duration_s)});
  const auto code = launch.wait(150s);
  const std::string out = launch.output();
  EXPECT_TRUE(code.has_value() && *code == 0) << out;
  const auto at = out.rfind("\n" + marker + ": ");
  if (at == std::string::npos) {
    ADD_FAILURE() << "no '" << marker << "' line:\n" << out;
    return -1.0;
  }
  return std::stod(out.substr(at + marker.size() + 3));
}

// deploy/demo_lockstep.yaml's simulation lasts 3 s of robot time, and its
// processes run until --duration (its header says 20 s).
constexpr int kDemoSeconds = 20;

TEST(DeployBackend, PdGravityDemoGivesTheSameFinalErrorWithDart) {
  if (!wbi::test::dart_built()) {
    GTEST_SKIP() << wbi::test::kDartMissing;
  }
  const std::string marker = "final max joint error";
  const auto wbi_file = deploy_variant("demo_lockstep.yaml", "bandwidth_hz: 5", "", "wbi");
  const auto dart_file = deploy_variant("demo_lockstep.yaml", "bandwidth_hz: 5",
                                        "          model_backend: dart", "dart");
  const double with_wbi = launch_summary(wbi_file, marker, kDemoSeconds);
  const double with_dart = launch_summary(dart_file, marker, kDemoSeconds);
  std::cout << "final max joint error: wbi " << with_wbi << " rad, dart " << with_dart << " rad\n";
  ASSERT_GT(with_wbi, 0.0);
  EXPECT_LT(with_wbi, 0.01);
  EXPECT_NEAR(with_dart, with_wbi, 1e-6);
}

TEST(DeployBackend, BalancingGivesTheSameComTrackingWithDart) {
  if (!wbi::test::dart_built()) {
    GTEST_SKIP() << wbi::test::kDartMissing;
  }
  // 5 s instead of 21 (DART's mass matrix is ~50× slower than ours).
  const std::string marker = "com tracking rms";
  auto variant = [&](const std::string& line, const std::string& tag) {
    const fs::path file = deploy_variant("balance.yaml", "exit_after_s: 21.0", line, tag);
    std::string text = wbi::test::read_text(file);
    wbi::test::replace_all(text, "exit_after_s: 21.0", "exit_after_s: 5.0");
    return wbi::test::write_test_file(file.filename().string(), text);
  };
  // The controller ends the run (shutdown_on_exit); --duration is a bound.
  const double with_wbi = launch_summary(variant("", "wbi"), marker, 120);
  const double with_dart =
      launch_summary(variant("          model_backend: dart", "dart"), marker, 120);
  std::cout << "com tracking rms: wbi " << with_wbi << " m, dart " << with_dart << " m\n";
  ASSERT_GT(with_wbi, 0.0);
  EXPECT_LT(with_wbi, 0.01);
  EXPECT_NEAR(with_dart, with_wbi, 0.02 * with_wbi);
}

}  // namespace
