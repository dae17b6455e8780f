// Several controllers on one robot (issue 22 item 2): `wbi launch
// deploy/balance_and_arms.yaml` runs the balancer (legs, torso) and PD +
// gravity (both arms) in separate processes on the humanoid, in lockstep; the
// robot grants each its joints, and the launch ends with both results under
// the bounds. Meanwhile a third controller that claims an arm joint is
// refused, naming the joint and its owner, and changes nothing.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

// The number after the last `marker` in `out`; NaN when absent.
double last_value(const std::string& out, const std::string& marker) {
  const auto at = out.rfind(marker);
  return at == std::string::npos ? std::nan("") : std::stod(out.substr(at + marker.size()));
}

TEST(BalanceAndArms, TwoControllersOwnTheirJointsAndBothMeetTheirBounds) {
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", (wbi::test::source_dir() / "deploy" / "balance_and_arms.yaml").string(),
       "--duration", "170"});
  ASSERT_TRUE(launch.wait_for_output("[robot] claims: 'arms'", 90s)) << launch.output();

  // An intruder: PD + gravity on the left elbow, in a process of its own.
  const auto intruder_file = wbi::test::binary_dir() / "tests" / "balance_intruder.yaml";
  std::ofstream(intruder_file)
      << "components:\n"
         "  - name: intruder\n"
         "    type: pd_gravity\n"
         "    parameters: {robot: humanoid, urdf: "
      << (wbi::test::source_dir() / "models" / "humanoid.urdf").string()
      << ", joints: [l_elbow], target: [1.0], max_age_s: 1.0, init_timeout_s: 30}\n";
  wbi::test::ChildProcess intruder(wbi::test::binary_dir() / "bin" / "wbi_host",
                                   {intruder_file.string()});
  const auto intruder_code = intruder.wait(60s);
  ASSERT_TRUE(intruder_code.has_value()) << intruder.output();
  EXPECT_NE(*intruder_code, 0) << intruder.output();
  EXPECT_NE(intruder.output().find("claim of 'intruder' refused: l_elbow (held by 'arms')"),
            std::string::npos)
      << intruder.output();

  const auto code = launch.wait(200s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  EXPECT_NE(out.find("[robot] claims: 'balance'"), std::string::npos) << out;
  EXPECT_NE(out.find("[robot] claim from 'intruder' rejected"), std::string::npos) << out;
  EXPECT_EQ(out.find("[robot] command from"), std::string::npos)
      << "no command was refused: each controller commands its own joints\n"
      << out;
  // Both results, the launch's last two lines, under the bounds.
  const auto rms_line = out.rfind("\ncom tracking rms: ");
  const auto arms_line = out.rfind("\nfinal max joint error: ");
  ASSERT_NE(rms_line, std::string::npos) << out;
  ASSERT_NE(arms_line, std::string::npos) << out;
  EXPECT_LT(rms_line, arms_line) << "in the file's summary order\n" << out;
  EXPECT_EQ(out.find('\n', arms_line + 1), out.size() - 1)
      << "the arms' result is not the last line\n"
      << out;
  EXPECT_LT(last_value(out, "\ncom tracking rms: "), 0.01) << out;
  EXPECT_LT(last_value(out, "\nfinal max joint error: "), 0.01) << out;
}

}  // namespace
