// CSV reading and writing for `wbi estimate`: errors name file, line and
// column; a file goes through read -> estimate -> write -> read intact.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "estimation_helpers.hpp"
#include "wbi/estimation/offline_filter.hpp"
#include "wbi/estimation/trajectory_csv.hpp"

namespace wbi::estimation::test {
namespace {

void expect_parse_error(const std::string& text, const std::string& message) {
  std::istringstream in(text);
  try {
    parse_joint_csv(in, "in.csv");
    ADD_FAILURE() << "no error for:\n" << text;
  } catch (const std::runtime_error& error) {
    EXPECT_EQ(std::string(error.what()), message);
  }
}

TEST(Csv, ParsesHeaderAndRows) {
  std::istringstream in("t, hip ,knee\r\n0,0.1,-0.2\n0.001,+0.15,-2.5e-1\n\n");
  const JointSamples samples = parse_joint_csv(in, "in.csv");
  EXPECT_EQ(samples.joint_names, (std::vector<std::string>{"hip", "knee"}));
  ASSERT_EQ(samples.t.size(), 2u);
  EXPECT_EQ(samples.t[1], 0.001);
  EXPECT_EQ(samples.q(1, 0), 0.15);
  EXPECT_EQ(samples.q(1, 1), -0.25);
}

TEST(Csv, ErrorsNameFileLineAndColumn) {
  expect_parse_error("", "in.csv: empty file, expected a header 't,<joint columns>'");
  expect_parse_error("time,a\n", "in.csv:1: the header must start with column 't', found 'time'");
  expect_parse_error("t\n0\n", "in.csv:1: the header names no joint column after 't'");
  expect_parse_error("t,a,,b\n", "in.csv:1: column 3 has an empty name");
  expect_parse_error("t,a,b\n0,1,2\n0.001,1\n",
                     "in.csv:3: expected 3 columns as in the header, found 2");
  expect_parse_error("t,a,b\n0,1,2\n0.001,1,x2\n", "in.csv:3: column 3 (b): 'x2' is not a number");
  expect_parse_error("t,a\n\n0,\n", "in.csv:3: column 2 (a): '' is not a number");
  expect_parse_error("t,a\nnan,1\n", "in.csv:2: column 1 (t): time must be finite");
}

TEST(Csv, MissingFileIsNamed) {
  EXPECT_THROW(read_joint_csv("/nonexistent/in.csv"), std::runtime_error);
}

TEST(Csv, RoundTripThroughTheOfflineFilter) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("wbi_test_estimation_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto input = dir / "in.csv";
  const auto output = dir / "out.csv";
  {
    std::ofstream out(input);
    out << "t,l_hip,r_knee,neck\n";
    for (int k = 0; k < 50; ++k) {
      const double t = 0.001 * k;
      out << t << "," << 0.5 * t << "," << -t * t << "," << 0.25 << "\n";
    }
    out << 0.049 << ",0,0,0\n";  // repeated stamp: ignored, estimates repeated
  }
  const JointSamples samples = read_joint_csv(input);
  const auto estimator = make_estimator("backward-difference", 3);
  const JointDerivatives derivatives = estimate_offline(*estimator, samples);
  write_derivatives_csv(output, derivatives);
  EXPECT_EQ(estimator->stamp_counters().duplicated, 1u);

  const JointSamples back = read_joint_csv(output);  // same shape: t then columns
  EXPECT_EQ(back.joint_names,
            (std::vector<std::string>{"dq0", "dq1", "dq2", "ddq0", "ddq1", "ddq2"}));
  ASSERT_EQ(back.t.size(), 51u);
  EXPECT_EQ(back.t, samples.t);
  for (Eigen::Index r = 0; r < 51; ++r) {
    for (Eigen::Index j = 0; j < 3; ++j) {
      EXPECT_EQ(back.q(r, j), derivatives.dq(r, j));  // shortest round-trip text is exact
      EXPECT_EQ(back.q(r, 3 + j), derivatives.ddq(r, j));
    }
  }
  EXPECT_NEAR(back.q(40, 0), 0.5, 1e-9);    // d/dt 0.5 t
  EXPECT_NEAR(back.q(40, 4), -2.0, 1e-6);   // d²/dt² -t²
  EXPECT_EQ(back.q(50, 0), back.q(49, 0));  // the ignored row repeats the estimate
  std::filesystem::remove_all(dir);
}

TEST(Csv, OfflineFilterChecksTheJointCount) {
  std::istringstream in("t,a,b\n0,1,2\n");
  const JointSamples samples = parse_joint_csv(in, "in.csv");
  const auto estimator = make_estimator("kalman", 3);
  EXPECT_THROW(estimate_offline(*estimator, samples), std::invalid_argument);
}

}  // namespace
}  // namespace wbi::estimation::test
