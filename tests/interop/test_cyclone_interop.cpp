// A second DDS implementation on the wire: wbi_interop_cyclone (Cyclone DDS,
// types from idl/*.idl by Cyclone's idlc, no wbi code) against a `wbi launch`
// deployment of the simulated arm, its estimator and its model service. The
// program checks the streams against the ground truth and moves a joint; this
// test checks its gravity vector against the model library.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "child_process.hpp"
#include "test_support.hpp"
#include "wbi/model/data.hpp"
#include "wbi/model/rnea.hpp"
#include "wbi/model/urdf.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

const std::string kProgram = WBI_CYCLONE_INTEROP_PROGRAM;

// The numbers after `prefix` on the line that starts with it; empty when none.
std::vector<double> numbers_after(const std::string& output, const std::string& prefix) {
  std::istringstream lines(output);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.rfind(prefix, 0) == 0) {
      std::istringstream values(line.substr(prefix.size()));
      std::vector<double> numbers;
      for (double value = 0.0; values >> value;) {
        numbers.push_back(value);
      }
      return numbers;
    }
  }
  return {};
}

TEST(CycloneInterop, ReadsCommandsAndCallsTheModelServiceOfAWbiRobot) {
  if (kProgram.empty()) {
    GTEST_SKIP() << "Cyclone DDS (or its idlc) not found when the build was configured "
                    "(apt-get install cyclonedds-dev cyclonedds-tools, or scripts/install-deps; "
                    "then re-run cmake)";
  }
  const auto source = wbi::test::source_dir();
  const auto deploy = source / "tests" / "interop" / "arm_for_a_foreign_client.yaml";
  ChildProcess launch(wbi::test::binary_dir() / "bin" / "wbi",
                      {"launch", deploy.string(), "--duration", "120"});

  // A posture away from the home one, so that every joint has a gravity torque to compare.
  const std::vector<double> q = {0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0};
  std::ostringstream q_text;
  for (std::size_t i = 0; i < q.size(); ++i) {
    q_text << (i == 0 ? "" : ",") << q[i];
  }
  const auto uri = "CYCLONEDDS_URI=file://" +
                   (source / "tests" / "interop" / "cyclonedds_loopback.xml").string();
  ChildProcess client(kProgram,
                      {"--robot", "arm", "--samples", "500", "--joint", "0", "--move", "0.2",
                       "--gravity-at", q_text.str(), "--timeout", "60"},
                      {uri});
  const auto code = client.wait(150s);
  const std::string out = client.output();
  ASSERT_TRUE(code.has_value()) << out << "\nlaunch:\n" << launch.output();
  EXPECT_EQ(*code, 0) << out << "\nlaunch:\n" << launch.output();
  std::cout << out;  // the figures of idl/README.md

  EXPECT_NE(out.find("description: 7 joints (joint_1 ... joint_7)"), std::string::npos) << out;
  EXPECT_NE(out.find("status: 'arm' (sim_robot) ACTIVE"), std::string::npos) << out;
  EXPECT_NE(out.find("command: joint_1 POSITION +0.200 rad"), std::string::npos) << out;

  const auto model = wbi::model::load_urdf_file(wbi::test::project_model("arm7.urdf").string());
  wbi::model::Data data(model);
  const Eigen::VectorXd expected = wbi::model::gravity_forces(
      model, data, Eigen::Map<const Eigen::VectorXd>(q.data(), static_cast<Eigen::Index>(q.size())),
      Eigen::Vector3d(0.0, 0.0, -9.81));
  const auto received = numbers_after(out, "gravity_forces:");
  ASSERT_EQ(received.size(), static_cast<std::size_t>(expected.size())) << out;
  for (std::size_t i = 0; i < received.size(); ++i) {
    EXPECT_NEAR(received[i], expected(static_cast<Eigen::Index>(i)),
                1e-9 * (1.0 + std::abs(expected(static_cast<Eigen::Index>(i)))))
        << "G[" << i << "]";
  }
  EXPECT_GT(expected.norm(), 1.0) << "a posture with gravity torques";

  launch.stop();
}

}  // namespace
