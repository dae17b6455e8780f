// deploy/balance.yaml runs in lockstep, so the same binary must give the same
// run every time, to the last printed digit, however the processes are
// scheduled. A start-up race once broke that: the controller's mode switch,
// sent before its first control step, could answer tick 0, and the robot
// stepped it with zero torque or with the first computed torques as timing
// decided (two outcomes; docs/conventions.md "Ticks and lockstep"). Here the
// balancing runs three times, 1 s of sinusoid after the 1 s of settling
// (exit_after_s: 2), with the controller's loop at 4 kHz, 1 kHz and 4 kHz (its
// rate changes the timing, not the lockstep run), and the summary lines must
// be equal.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

void replace_one(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "'" << from << "' not in deploy/balance.yaml";
  text.replace(at, from.size(), to);
}

// deploy/balance.yaml with absolute paths, 2 s long, the controller at `rate_hz`.
fs::path short_balance(int rate_hz) {
  const fs::path deploy = wbi::test::source_dir() / "deploy";
  std::ifstream in(deploy / "balance.yaml");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  for (auto at = text.find("../models/"); at != std::string::npos;
       at = text.find("../models/", at + 1)) {
    text.replace(at, 10, (wbi::test::source_dir() / "models").string() + "/");
  }
  replace_one(text, "config: robots/", "config: " + (deploy / "robots").string() + "/");
  replace_one(text, "exit_after_s: 21.0", "exit_after_s: 2.0");
  replace_one(text, "rate_hz: 4000", "rate_hz: " + std::to_string(rate_hz));
  const fs::path out = wbi::test::binary_dir() / "tests" /
                       ("balance_lockstep_repeats_" + std::to_string(rate_hz) + ".yaml");
  std::ofstream(out) << text;
  return out;
}

// The controller's summary: "[controller] max com error: ..." and
// "[controller] com tracking rms: ...".
std::string summary(const std::string& out) {
  std::string lines;
  for (const std::string key :
       {"[controller] max com error: ", "[controller] com tracking rms: "}) {
    const auto at = out.rfind(key);
    if (at == std::string::npos) {
      ADD_FAILURE() << "no '" << key << "' line:\n" << out;
      return {};
    }
    lines += out.substr(at, out.find('\n', at) - at + 1);
  }
  return lines;
}

TEST(BalanceLockstep, RepeatsToTheLastDigit) {
  std::vector<std::string> summaries;
  for (const int rate_hz : {4000, 1000, 4000}) {
    const auto start = std::chrono::steady_clock::now();
    wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                                   {"launch", short_balance(rate_hz).string(), "--duration", "60"});
    const auto code = launch.wait(80s);
    ASSERT_TRUE(code.has_value()) << launch.output();
    const std::string out = launch.output();
    ASSERT_EQ(*code, 0) << out;
    EXPECT_NE(out.find("[controller] qp failures: 0\n"), std::string::npos) << out;
    EXPECT_EQ(out.find("not answered by every controller"), std::string::npos) << out;
    summaries.push_back(summary(out));
    std::cout << "controller at " << rate_hz << " Hz, "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s:\n"
              << summaries.back();
  }
  EXPECT_EQ(summaries[1], summaries[0]);
  EXPECT_EQ(summaries[2], summaries[0]);
}

}  // namespace
