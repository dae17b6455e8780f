// A controller's reference stream stops: the lockstep humanoid balancing of
// deploy/balance.yaml (8 s long), its CoM reference from the com_sinusoid
// generator in a process of its own (`reference`, not respawned), which the
// test kills (SIGKILL) past t = 3 s. The balancer's input
// `com` goes stale: the controller says so once (rule decay_to_state), counts
// the stale ticks in one episode, is not held up by its lockstep wait for the
// dead generator, and the robot stands to the end of the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <regex>
#include <sstream>
#include <string>

#include <sys/types.h>
#include <unistd.h>

#include "child_process.hpp"
#include "deploy_text.hpp"
#include "progress_lines.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// deploy/balance.yaml with absolute paths, 8 s long, no respawn (a crash is a
// failure here), its com_reference component moved to a process of its own
// ("reference", not required: its death does not end the launch), started once
// the state is published, as the controller is.
fs::path write_deploy(const fs::path& dir) {
  std::string text = wbi::test::deploy_text("balance.yaml");
  wbi::test::replace_all(text, "exit_after_s: 21.0", "exit_after_s: 8.0");
  // The generator's process may start after the controller's first tick: that
  // tick waits reference_wait_s (0.5 s, shorter than max_age_s, so that the
  // state it answers is not stale by then) and the balancer holds the measured
  // CoM until the first point.
  wbi::test::replace_all(text, "    respawn: {enabled: true, delay: 0.5, max_retries: 3}\n", "");
  const auto generator_at = text.find("      - name: com_reference\n");
  const auto joints_at = text.find("joints: &joints");
  const auto joints_end = text.find(']', joints_at);
  if (generator_at == std::string::npos || joints_at == std::string::npos ||
      joints_end == std::string::npos || text.find("respawn:") != std::string::npos) {
    ADD_FAILURE() << "deploy/balance.yaml changed: no com_reference component, joints anchor, "
                     "or a respawn this test does not remove\n"
                  << text;
    return {};
  }
  const std::string joints = text.substr(joints_at + 16, joints_end + 1 - (joints_at + 16));
  std::string generator = text.substr(generator_at);
  wbi::test::replace_all(generator, "joints: *joints", "joints: " + joints);
  text.erase(text.rfind('\n', text.rfind("# The CoM reference", generator_at)) + 1);
  text +=
      "  - name: reference\n"
      "    required: false\n"
      "    wait_for: {topics: [wbi/humanoid/state], timeout: 30}\n"
      "    components:\n" +
      generator;
  const fs::path deploy = dir / "balance_own_reference.yaml";
  std::ofstream(deploy) << text;
  return deploy;
}

// The pid `wbi launch` gave a process ("[launch] NAME: started (pid N)").
std::optional<pid_t> started_pid(const std::string& out, const std::string& name) {
  const std::regex started("\\[launch\\] " + name + ": started \\(pid ([0-9]+)\\)");
  std::smatch match;
  if (!std::regex_search(out, match, started)) {
    return std::nullopt;
  }
  return static_cast<pid_t>(std::stol(match[1].str()));
}

// The count before `label` in the controller's summary line of the input.
std::optional<long> reference_count(const std::string& out, const std::string& label) {
  const std::regex summary("\\[controller\\] reference balance/com: .*");
  std::smatch line;
  if (!std::regex_search(out, line, summary)) {
    return std::nullopt;
  }
  const std::regex count("([0-9]+) " + label);
  std::smatch match;
  const std::string text = line.str();
  if (!std::regex_search(text, match, count)) {
    return std::nullopt;
  }
  return std::stol(match[1].str());
}

TEST(ReferenceStreamStops, BalancerDecaysToTheStateAndStands) {
  const fs::path dir =
      fs::temp_directory_path() / ("wbi_reference_stream_stops_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path deploy = write_deploy(dir);
  ASSERT_FALSE(deploy.empty());
  wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                                 {"launch", deploy.string(), "--duration", "150"});
  const auto past = [&](double t) {
    const auto times = wbi::test::progress_times(launch.output());
    return !times.empty() && times.back() >= t;
  };
  ASSERT_TRUE(wbi::test::eventually([&] { return past(3.0) || !launch.running(); }, 120s))
      << launch.output();
  ASSERT_TRUE(past(3.0)) << "the launch ended before t = 3 s\n" << launch.output();
  const std::string before_kill = launch.output();
  EXPECT_EQ(before_kill.find("stale (older than"), std::string::npos)
      << "stale before the generator died\n"
      << before_kill;
  const auto generator = started_pid(before_kill, "reference");
  ASSERT_TRUE(generator.has_value()) << before_kill;
  ASSERT_EQ(::kill(*generator, SIGKILL), 0) << "pid " << *generator;

  // 5 s of simulated time more; a tick waiting reference_wait_s (0.5 s) for the
  // dead generator each would take 5000 s.
  const auto code = launch.wait(120s);
  const std::string out = launch.output();
  ASSERT_TRUE(code.has_value()) << "the run did not end within 120 s of the kill\n" << out;
  // The controller ended the run; the launch fails: a process it started was killed.
  EXPECT_EQ(*code, 1) << out;
  EXPECT_NE(out.find("  controller: exit code 0\n"), std::string::npos) << out;
  EXPECT_NE(out.find("  reference: exit code 137: FAILED, ended in error\n"), std::string::npos)
      << out;
  const auto times = wbi::test::progress_times(out);
  ASSERT_FALSE(times.empty()) << out;
  // The last progress line may be t = 7 or t = 8: the controller ends the run
  // at its t = 8 s, which may come a tick before the host's. The robot's count
  // of simulated ticks says whether the run reached its end.
  EXPECT_GE(times.back(), 7.0) << "the run ended early\n" << out;
  const std::regex simulated("ground truth over ([0-9]+) ticks");
  std::smatch ticks;
  ASSERT_TRUE(std::regex_search(out, ticks, simulated)) << out;
  EXPECT_GE(std::stol(ticks[1].str()), 8000) << "the run ended before t = 8 s\n" << out;

  const std::regex said(
      "\\[controller\\] t = ([0-9.]+) s: reference balance/com stale \\(older than 0\\.050 s\\): "
      "rule decay_to_state");
  std::smatch stale;
  ASSERT_TRUE(std::regex_search(out, stale, said)) << out;
  const double stale_at = std::stod(stale[1].str());
  EXPECT_GE(stale_at, 3.0) << out;
  EXPECT_EQ(
      std::distance(std::sregex_iterator(out.begin(), out.end(), said), std::sregex_iterator()), 1)
      << "said once per episode\n"
      << out;

  const auto stale_ticks = reference_count(out, "stale in 1 episodes \\(rule decay_to_state\\)");
  ASSERT_TRUE(stale_ticks.has_value()) << "no summary line with 1 stale episode\n" << out;
  EXPECT_GT(*stale_ticks, 1000) << "about 1 kHz from the kill to t = 8 s\n" << out;
  const auto late = reference_count(out, "points late");
  ASSERT_TRUE(late.has_value()) << out;
  EXPECT_LE(*late, 2) << "the dead generator's wait timed out once\n" << out;

  // Standing after the stop: the progress lines' CoM height and error.
  const std::regex progress(
      "\\[controller\\] t = +([0-9.]+) s  com \\(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\\) m  "
      "error ([0-9.]+) m");
  double error_after = 0.0, lowest_com = 1.0;
  int lines_after = 0;
  for (auto it = std::sregex_iterator(out.begin(), out.end(), progress);
       it != std::sregex_iterator(); ++it) {
    if (std::stod((*it)[1].str()) > stale_at) {
      ++lines_after;
      error_after = std::max(error_after, std::stod((*it)[5].str()));
      lowest_com = std::min(lowest_com, std::stod((*it)[4].str()));
    }
  }
  EXPECT_GE(lines_after, 4) << out;
  EXPECT_LT(error_after, 0.02) << out;
  EXPECT_GT(lowest_com, 0.5) << "the CoM stays at its standing height (0.55 m)\n" << out;

  EXPECT_NE(out.find("[controller] qp failures: 0\n"), std::string::npos) << out;
  const auto max_error = wbi::test::last_value_after(out, "[controller] max com error: ");
  const auto rms = wbi::test::last_value_after(out, "[controller] com tracking rms: ");
  ASSERT_TRUE(max_error.has_value() && rms.has_value()) << out;
  EXPECT_LT(*max_error, 0.02) << out;
  EXPECT_LT(*rms, 0.01) << out;
  std::cout << "generator killed past t = 3 s; stale from t = " << stale_at << " s, "
            << *stale_ticks << " stale ticks in 1 episode, " << *late
            << " late; after it: CoM error at most " << error_after << " m, CoM height at least "
            << lowest_com << " m; the run's max com error " << *max_error << " m, rms " << *rms
            << " m\n";
  if (!HasFailure()) {
    fs::remove_all(dir);
  }
}

}  // namespace
