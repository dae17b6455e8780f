// deepest_frame / time_algorithms / timing_json / write_timing_text with the "wbi"
// backend on the arm and the humanoid (few states and calls: the figures are not
// the point, their presence and order are).
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <wbi/model/backend.hpp>
#include <wbi/model_inspect/algorithm_timing.hpp>

#include "test_support.hpp"

namespace wm = wbi::model;
namespace inspect = wbi::model_inspect;

namespace {

const std::vector<std::string> kOperations{
    "mass_matrix_ns",        "bias_forces_ns",
    "gravity_forces_ns",     "inverse_dynamics_ns",
    "forward_dynamics_ns",   "jacobian_ns",
    "forward_kinematics_ns", "centroidal_momentum_matrix_ns"};

std::unique_ptr<wm::ModelBackend> backend_of(const char* file) {
  return wm::make_model_backend("wbi", wbi::test::project_model(file).string());
}

int depth(const wm::Model& m, int body) {
  int d = 0;
  for (int i = body; i > 0; i = m.parent[static_cast<std::size_t>(i)]) {
    ++d;
  }
  return d;
}

}  // namespace

TEST(AlgorithmTiming, DeepestFrameIsTheFirstFrameOnTheArmsLastLink) {
  const auto arm = backend_of("arm7.urdf");
  const wm::Model& m = arm->model();
  const int frame = inspect::deepest_frame(m);
  // link_7, ee_link and tool_frame are all on the last body; the first of them wins.
  EXPECT_EQ(m.frame_body[static_cast<std::size_t>(frame)],
            m.frame_body[static_cast<std::size_t>(m.frame_id("tool_frame"))]);
  EXPECT_EQ(depth(m, m.frame_body[static_cast<std::size_t>(frame)]), 7);
  for (int f = 0; f < frame; ++f) {
    EXPECT_LT(depth(m, m.frame_body[static_cast<std::size_t>(f)]), 7) << m.frame_name[f];
  }
}

TEST(AlgorithmTiming, DeepestFrameOfTheHumanoidIsAsDeepAsAnyFrame) {
  const auto humanoid = backend_of("humanoid.urdf");
  const wm::Model& m = humanoid->model();
  const int deepest = depth(m, m.frame_body[static_cast<std::size_t>(inspect::deepest_frame(m))]);
  for (int f = 0; f < m.n_frames(); ++f) {
    EXPECT_LE(depth(m, m.frame_body[static_cast<std::size_t>(f)]), deepest);
  }
  EXPECT_GE(deepest, 3);  // a hand or a foot, not the pelvis
}

TEST(AlgorithmTiming, ReportsEveryOperationInOrderWithPositiveTimes) {
  const auto arm = backend_of("arm7.urdf");
  const inspect::TimingReport report = inspect::time_algorithms(*arm, 3, 2);
  EXPECT_EQ(report.model, arm->model().name);
  EXPECT_EQ(report.backend, "wbi");
  EXPECT_EQ(report.nv, 7);
  EXPECT_EQ(report.states, 3);
  EXPECT_EQ(
      report.jacobian_frame,
      arm->model().frame_name[static_cast<std::size_t>(inspect::deepest_frame(arm->model()))]);
  ASSERT_EQ(report.timings.size(), kOperations.size());
  for (std::size_t k = 0; k < kOperations.size(); ++k) {
    EXPECT_EQ(report.timings[k].key, kOperations[k]);
    EXPECT_GT(report.timings[k].median_ns, 0.0) << kOperations[k];
  }

  const nlohmann::json json = inspect::timing_json(report);
  EXPECT_EQ(json["nv"], 7);
  EXPECT_EQ(json["jacobian_frame"], report.jacobian_frame);
  for (const auto& timing : report.timings) {
    EXPECT_EQ(json[timing.key].get<double>(), timing.median_ns);
  }

  std::ostringstream text;
  inspect::write_timing_text(text, report);
  std::istringstream lines(text.str());
  std::string line;
  std::getline(lines, line);
  EXPECT_NE(line.find("nv = 7, backend wbi, median ns per call over 3 random states:"),
            std::string::npos)
      << line;
  for (const auto& key : kOperations) {
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(line.rfind("  " + key + " ", 0), 0u) << line;
  }
  ASSERT_TRUE(std::getline(lines, line));
  EXPECT_NE(line.find("frame '" + report.jacobian_frame + "'"), std::string::npos) << line;
}

TEST(AlgorithmTiming, RefusesNoStatesOrNoCalls) {
  const auto arm = backend_of("arm7.urdf");
  EXPECT_THROW(inspect::time_algorithms(*arm, 0, 5), std::invalid_argument);
  EXPECT_THROW(inspect::time_algorithms(*arm, 5, 0), std::invalid_argument);
}
