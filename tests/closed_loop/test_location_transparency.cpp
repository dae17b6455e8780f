// Location transparency: the same controller, the same components, only the
// deploy file differs — three processes, or one (a deploy file of its own, or
// `wbi launch --one-process`); the model evaluated in the
// controller's process, or by the model service in a fourth — and in lockstep
// the run ends with the same final error to the last printed digit (the
// remote model runs the same model library on the same inputs, sent as exact
// doubles, so no tolerance is needed).
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

// Runs a deploy file (3 s of simulated time in lockstep) and returns its last line.
std::string final_line(const std::string& deploy, const std::string& launch_flag = "") {
  // The launch lasts 20 s of wall time: the simulation stops stepping at 3 s of
  // its own time long before, and the controller reports where it ended.
  std::vector<std::string> args{"launch", (wbi::test::source_dir() / "deploy" / deploy).string(),
                                "--duration", "20"};
  if (!launch_flag.empty()) {
    args.push_back(launch_flag);
  }
  wbi::test::ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi", args);
  const auto code = launch.wait(120s);
  const std::string out = launch.output();
  EXPECT_TRUE(code.has_value() && *code == 0) << out;
  const auto end = out.find_last_not_of('\n');
  const auto start = out.rfind('\n', end);
  const std::string last = out.substr(start + 1, end - start);
  EXPECT_EQ(last.rfind("final max joint error: ", 0), 0u) << out;
  EXPECT_EQ(out.find("not answered"), std::string::npos) << "a lockstep tick timed out:\n" << out;
  return last;
}

// The three-process run both comparisons start from, launched once.
const std::string& three_processes() {
  static const std::string last = final_line("demo_lockstep.yaml");
  return last;
}

TEST(LocationTransparency, OneProcessOrThreeGiveTheSameRun) {
  const std::string& three = three_processes();
  const std::string one = final_line("demo_lockstep_one_process.yaml");
  EXPECT_EQ(three, one);
  const double error = std::stod(three.substr(std::string("final max joint error: ").size()));
  EXPECT_LT(error, 0.01);
}

// `wbi launch --one-process`: the three-process deploy file hosted by one wbi_host.
TEST(LocationTransparency, LaunchedAsOneProcessGivesTheSameRun) {
  EXPECT_EQ(three_processes(), final_line("demo_lockstep.yaml", "--one-process"));
}

TEST(LocationTransparency, LocalOrRemoteModelGiveTheSameRun) {
  const std::string remote = final_line("demo_lockstep_remote_model.yaml");
  EXPECT_EQ(three_processes(), remote);
}

}  // namespace
