// read_state / evaluate_state with the "wbi" backend on the arm and the humanoid:
// the results equal the model library's, follow a caller's joint order, and every
// bad state is refused naming what is wrong.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include <wbi/model/algorithms.hpp>
#include <wbi/model_inspect/state_evaluation.hpp>

#include "json_eigen.hpp"
#include "test_support.hpp"

namespace wm = wbi::model;
namespace inspect = wbi::model_inspect;
using nlohmann::json;

namespace {

std::unique_ptr<wm::ModelBackend> backend_of(const char* file) {
  return wm::make_model_backend("wbi", wbi::test::project_model(file).string());
}

Eigen::MatrixXd matrix_of(const json& rows) { return wbi::test::matrix_of_json(rows); }
Eigen::VectorXd vector_of(const json& v) { return wbi::test::vector_of_json(v); }

// The message of the std::runtime_error that evaluate_state throws, "" if none.
std::string error_of(const char* file, const json& state) {
  const auto backend = backend_of(file);
  try {
    inspect::evaluate_state(*backend, state);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// A file in the temporary directory, its name made unique by the process id (two
// build trees may run this test at the same time).
std::filesystem::path temp_file(const std::string& name, const std::string& text) {
  const auto path =
      std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(StateEvaluation, ArmMatchesTheModelLibrary) {
  const auto backend = backend_of("arm7.urdf");
  const wm::Model& model = backend->model();
  std::mt19937 rng(7);
  const Eigen::VectorXd q = wm::random_configuration(model, rng);
  const Eigen::VectorXd dq = Eigen::VectorXd::LinSpaced(model.nv, -1.0, 1.0);
  const Eigen::Vector3d g(0.0, 0.0, -3.7);  // not the default, so that 'gravity' is read
  const json state{{"q", std::vector<double>(q.data(), q.data() + q.size())},
                   {"dq", std::vector<double>(dq.data(), dq.data() + dq.size())},
                   {"gravity", {g.x(), g.y(), g.z()}},
                   {"frames", {"tool_frame"}}};
  const json out = inspect::evaluate_state(*backend, state);

  wm::Data data(model);
  EXPECT_EQ(out["backend"], "wbi");
  EXPECT_EQ(out["joints"].get<std::vector<std::string>>(), model.joint_name);
  EXPECT_TRUE(matrix_of(out["mass_matrix"]).isApprox(wm::mass_matrix(model, data, q), 1e-12));
  EXPECT_TRUE(
      vector_of(out["bias_forces"]).isApprox(wm::bias_forces(model, data, q, dq, g), 1e-12));
  EXPECT_TRUE(
      vector_of(out["gravity_forces"]).isApprox(wm::gravity_forces(model, data, q, g), 1e-12));
  EXPECT_TRUE(vector_of(out["com"]).isApprox(wm::center_of_mass(model, data, q), 1e-12));
  const int tool = model.frame_id("tool_frame");
  wm::forward_kinematics(model, data, q);
  const json& frame = out["frames"]["tool_frame"];
  EXPECT_TRUE(matrix_of(frame["transform"]).isApprox(wm::frame_pose(model, data, tool), 1e-12));
  EXPECT_TRUE(matrix_of(frame["jacobian"]).isApprox(wm::frame_jacobian(model, data, tool), 1e-12));
  EXPECT_EQ(frame["dJnu"].size(), 6u);
}

TEST(StateEvaluation, DefaultStateIsTheNeutralConfigurationAtRest) {
  const auto backend = backend_of("arm7.urdf");
  const wm::Model& model = backend->model();
  const json out = inspect::evaluate_state(*backend, json::object());
  wm::Data data(model);
  const Eigen::VectorXd q0 = wm::neutral_configuration(model);
  const Eigen::VectorXd G = wm::gravity_forces(model, data, q0, Eigen::Vector3d(0.0, 0.0, -9.81));
  EXPECT_GT(G.norm(),
            0.1);  // the arm's weight is felt (0.46 N m), so the checks below mean something
  EXPECT_LT((vector_of(out["gravity_forces"]) - G).norm(), 1e-12 * G.norm());
  EXPECT_LT((vector_of(out["bias_forces"]) - G).norm(), 1e-12 * G.norm());  // at rest h = G
  EXPECT_EQ(vector_of(out["centroidal_momentum"]), Eigen::VectorXd::Zero(6));
  EXPECT_EQ(out["frames"], json::object());
}

TEST(StateEvaluation, ResultsFollowTheCallersJointOrder) {
  const auto backend = backend_of("humanoid.urdf");
  const wm::Model& model = backend->model();
  const auto n = static_cast<std::size_t>(model.n_joints);
  std::vector<std::string> reversed(model.joint_name.rbegin(), model.joint_name.rend());
  std::vector<double> q(n);
  for (std::size_t k = 0; k < n; ++k) {
    q[k] = 0.02 * static_cast<double>(k) - 0.3;
  }
  const std::vector<double> q_model(q.rbegin(), q.rend());
  const json mine = inspect::evaluate_state(*backend, {{"joints", reversed}, {"q", q}});
  const json theirs = inspect::evaluate_state(*backend, {{"q", q_model}});
  const Eigen::MatrixXd M = matrix_of(mine["mass_matrix"]);
  const Eigen::MatrixXd M_model = matrix_of(theirs["mass_matrix"]);
  ASSERT_EQ(M.rows(), static_cast<Eigen::Index>(n + 6));
  // caller index i (after the base's 6) is model index 6 + n - 1 - (i - 6)
  auto model_index = [&](Eigen::Index i) {
    return i < 6 ? i : static_cast<Eigen::Index>(6 + n - 1) - (i - 6);
  };
  for (Eigen::Index i = 0; i < M.rows(); ++i) {
    EXPECT_EQ(mine["gravity_forces"][static_cast<std::size_t>(i)],
              theirs["gravity_forces"][static_cast<std::size_t>(model_index(i))]);
    for (Eigen::Index j = 0; j < M.cols(); ++j) {
      EXPECT_EQ(M(i, j), M_model(model_index(i), model_index(j)));
    }
  }
}

TEST(StateEvaluation, BadStatesAreRefusedNamingTheProblem) {
  EXPECT_EQ(error_of("arm7.urdf", {{"qq", {1}}}), "state: unknown key 'qq'");
  EXPECT_EQ(error_of("arm7.urdf", {{"q", {1, 2}}}),
            "state: 'q' must be an array of 7 numbers, got 2");
  EXPECT_EQ(error_of("arm7.urdf", {{"q", {1, 2, 3, 4, 5, 6, "x"}}}),
            "state: 'q'[6] is not a number");
  EXPECT_EQ(error_of("arm7.urdf", {{"base_position", {0, 0, 1}}}),
            "state: 'base_position' given, but the model has a fixed base");
  EXPECT_EQ(error_of("arm7.urdf", {{"joints", {"joint_1"}}}),
            "state: 'joints' must list every joint of the model; 'joint_2' is missing");
  EXPECT_EQ(error_of("arm7.urdf", {{"joints", {"joint_1", "joint_1"}}}),
            "state: joint 'joint_1' appears twice in 'joints'");
  EXPECT_EQ(error_of("arm7.urdf", {{"joints", {"elbow"}}}),
            "state: unknown joint 'elbow' in 'joints'");
  EXPECT_EQ(error_of("arm7.urdf", {{"frames", {"nose"}}}), "state: unknown frame 'nose'");
  EXPECT_NE(error_of("humanoid.urdf", {{"base_quaternion", {1, 0, 0, 1}}})
                .find("'base_quaternion' [w,x,y,z] has norm 1.41"),
            std::string::npos);
  EXPECT_EQ(error_of("humanoid.urdf", {{"base_velocity", {0, 0, 0}}}),
            "state: 'base_velocity' must be an array of 6 numbers, got 3");
}

TEST(StateEvaluation, ReadStateReadsAnObjectAndNamesTheFileOtherwise) {
  const auto good = temp_file("wbi_inspect_state_good.json", R"({"q": [0.5]})");
  EXPECT_EQ(inspect::read_state(good.string()), json({{"q", {0.5}}}));
  auto error_of_file = [](const std::string& where) -> std::string {
    try {
      inspect::read_state(where);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_of_file("/no/such/state.json"), "state file '/no/such/state.json': cannot open");
  const auto array = temp_file("wbi_inspect_state_array.json", "[1, 2]");
  EXPECT_EQ(error_of_file(array.string()),
            "state '" + array.string() + "': expected a JSON object");
  const auto broken = temp_file("wbi_inspect_state_broken.json", "{\"q\": ");
  EXPECT_EQ(
      error_of_file(broken.string()).rfind("state '" + broken.string() + "': JSON error: ", 0), 0u);
  for (const auto& file : {good, array, broken}) {
    std::filesystem::remove(file);
  }
}
