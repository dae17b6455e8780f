// deploy/icub3_switch.yaml, as a user runs it: iCub 3 in MuJoCo stands in
// hold, is switched to the balancer at t = 1 s and back to hold at t = 12 s by
// the host's schedule (lockstep, three processes). Each switch continues the
// last command (torque step 0), the balancer tracks its CoM within 1 cm, the
// feet do not slip, and the launch ends at t = 15 s with exit code 0.
#include <gtest/gtest.h>

#include <chrono>
#include <regex>
#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

double number_after(const std::string& text, const std::string& marker) {
  const auto at = text.rfind(marker);
  if (at == std::string::npos) {
    ADD_FAILURE() << "no '" << marker << "' in\n" << text;
    return 1e9;
  }
  return std::stod(text.substr(at + marker.size()));
}

TEST(Icub3Switch, HoldBalanceHoldWithoutATorqueStep) {
  if (!wbi::test::shared_models_dir()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / "icub3_switch.yaml").string()});
  const auto code = launch.wait(240s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  const std::regex switch_line(
      R"(switch: (\w+) → (\w+) at t = ([0-9.]+) s; torque step ([0-9.]+) %)");
  std::vector<std::string> switches;
  for (std::sregex_iterator it(out.begin(), out.end(), switch_line), end; it != end; ++it) {
    switches.push_back((*it)[1].str() + "→" + (*it)[2].str() + "@" + (*it)[3].str());
    EXPECT_LT(std::stod((*it)[4].str()), 5.0) << it->str();
  }
  EXPECT_EQ(switches, (std::vector<std::string>{"hold→balance@1.000", "balance→hold@12.000"}))
      << out;
  EXPECT_LT(number_after(out, "max com error: "), 0.01) << out;
  EXPECT_LT(number_after(out, "contact slip: "), 5.0) << "mm\n" << out;
}

}  // namespace
