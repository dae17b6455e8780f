// The `wbi model` verb (cli/src/verbs/model.cpp), called in-process: JSON out
// of `eval` equals the library's results (also with a caller joint order and a
// reduced model); `info` and `bench` print the documented keys; bad input
// throws the documented errors.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "json_eigen.hpp"
#include "model_test_common.hpp"
#include "verb.hpp"

namespace wbi::cli {
int run_model(Args args);
}

namespace wm = wbi::model;
using nlohmann::json;

namespace {

// Runs `wbi model <args>` and returns its standard output.
std::string run(const std::vector<std::string>& args) {
  std::ostringstream captured;
  std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
  try {
    const int rc = wbi::cli::run_model(args);
    std::cout.rdbuf(old);
    EXPECT_EQ(rc, 0);
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  return captured.str();
}

std::string write_state(const json& state) {
  const auto path = std::filesystem::temp_directory_path() / "wbi_model_test_state.json";
  std::ofstream(path) << state.dump();
  return path.string();
}

Eigen::MatrixXd matrix(const json& rows) { return wbi::test::matrix_of_json(rows); }
Eigen::VectorXd vector(const json& v) { return wbi::test::vector_of_json(v); }

std::string humanoid() { return wbi::test::project_model("humanoid.urdf").string(); }

}  // namespace

TEST(Cli, EvalMatchesLibraryInModelOrder) {
  ASSERT_TRUE(std::filesystem::exists(humanoid())) << humanoid() << ": a model of this project";
  const wm::Model model = wm::load_urdf_file(humanoid());
  wm::Data data(model);
  std::mt19937 rng(1);
  const Eigen::VectorXd q = wm::random_configuration(model, rng);
  const Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 1.0);
  json state;
  state["q"] = std::vector<double>(q.data() + 7, q.data() + model.nq);
  state["dq"] = std::vector<double>(nu.data() + 6, nu.data() + model.nv);
  state["base_position"] = std::vector<double>(q.data(), q.data() + 3);
  state["base_quaternion"] = std::vector<double>(q.data() + 3, q.data() + 7);
  state["base_velocity"] = std::vector<double>(nu.data(), nu.data() + 6);
  state["gravity"] = {0.0, 0.0, -9.81};
  state["frames"] = {model.frame_name.back()};
  const json out = json::parse(run({"eval", humanoid(), "--state", write_state(state)}));
  const Eigen::Vector3d g(0, 0, -9.81);
  EXPECT_EQ(out["joints"].get<std::vector<std::string>>(), model.joint_name);
  EXPECT_TRUE(
      wbi::test::near_rel(matrix(out["mass_matrix"]), wm::mass_matrix(model, data, q), 1e-12));
  EXPECT_TRUE(wbi::test::near_rel(vector(out["bias_forces"]),
                                  wm::bias_forces(model, data, q, nu, g), 1e-12));
  EXPECT_TRUE(wbi::test::near_rel(vector(out["gravity_forces"]),
                                  wm::gravity_forces(model, data, q, g), 1e-12));
  EXPECT_NEAR(out["total_mass"].get<double>(), model.total_mass, 1e-12);
  EXPECT_TRUE(wbi::test::near_rel(vector(out["com"]), wm::center_of_mass(model, data, q), 1e-12));
  EXPECT_TRUE(wbi::test::near_rel(vector(out["centroidal_momentum"]),
                                  wm::centroidal_momentum(model, data, q, nu), 1e-12));
  const json& f = out["frames"][model.frame_name.back()];
  wm::forward_velocity_kinematics(model, data, q, nu);
  const int id = model.n_frames() - 1;
  EXPECT_TRUE(wbi::test::near_rel(matrix(f["transform"]), wm::frame_pose(model, data, id), 1e-12));
  EXPECT_TRUE(
      wbi::test::near_rel(matrix(f["jacobian"]), wm::frame_jacobian(model, data, id), 1e-12));
  EXPECT_TRUE(
      wbi::test::near_rel(vector(f["dJnu"]), wm::frame_bias_acceleration(model, data, id), 1e-12));
}

TEST(Cli, EvalFollowsTheCallersJointOrder) {
  ASSERT_TRUE(std::filesystem::exists(humanoid())) << humanoid() << ": a model of this project";
  const wm::Model model = wm::load_urdf_file(humanoid());
  std::vector<std::string> reversed(model.joint_name.rbegin(), model.joint_name.rend());
  std::vector<double> q(static_cast<std::size_t>(model.n_joints));
  for (std::size_t k = 0; k < q.size(); ++k) {
    q[k] = 0.01 * static_cast<double>(k);
  }
  json state{{"joints", reversed}, {"q", q}};
  const json out = json::parse(run({"eval", humanoid(), "--state", write_state(state)}));
  EXPECT_EQ(out["joints"].get<std::vector<std::string>>(), reversed);
  // the same state in model order
  std::vector<double> q_model(q.rbegin(), q.rend());
  const json ref =
      json::parse(run({"eval", humanoid(), "--state", write_state(json{{"q", q_model}})}));
  const Eigen::MatrixXd M = matrix(out["mass_matrix"]);
  const Eigen::MatrixXd M_ref = matrix(ref["mass_matrix"]);
  const int n = model.n_joints;
  for (int i = 0; i < 6 + n; ++i) {
    const int pi = i < 6 ? i : 6 + (n - 1 - (i - 6));
    EXPECT_NEAR(out["gravity_forces"][static_cast<std::size_t>(i)].get<double>(),
                ref["gravity_forces"][static_cast<std::size_t>(pi)].get<double>(), 1e-12);
    for (int j = 0; j < 6 + n; ++j) {
      const int pj = j < 6 ? j : 6 + (n - 1 - (j - 6));
      EXPECT_NEAR(M(i, j), M_ref(pi, pj), 1e-12);
    }
  }
}

TEST(Cli, FixedBaseAndReducedSizes) {
  const std::string pendulum = wbi::test::project_model("double_pendulum.urdf").string();
  const json out =
      json::parse(run({"eval", pendulum, "--state", write_state(json{{"q", {0.1, 0.2}}})}));
  EXPECT_EQ(out["mass_matrix"].size(), 2u);
  EXPECT_EQ(out["bias_forces"].size(), 2u);
  const json red = json::parse(
      run({"eval", pendulum, "--joints", "joint2", "--state", write_state(json{{"q", {0.2}}})}));
  EXPECT_EQ(red["mass_matrix"].size(), 1u);
  EXPECT_EQ(red["joints"].get<std::vector<std::string>>(), std::vector<std::string>{"joint2"});
}

TEST(Cli, InfoAndBenchKeys) {
  const std::string pendulum = wbi::test::project_model("pendulum.urdf").string();
  const json info = json::parse(run({"info", pendulum, "--json"}));
  EXPECT_EQ(info["base"], "fixed");
  EXPECT_EQ(info["joints"][0]["name"], "hinge");
  EXPECT_DOUBLE_EQ(info["joints"][0]["effort"].get<double>(), 50.0);
  EXPECT_DOUBLE_EQ(info["total_mass"].get<double>(), 2.0);
  EXPECT_EQ(info["frames"].size(), 3u);
  EXPECT_FALSE(run({"info", pendulum}).empty());
  const json bench =
      json::parse(run({"bench", pendulum, "--json", "--states", "3", "--batch", "2"}));
  for (const char* key :
       {"mass_matrix_ns", "bias_forces_ns", "gravity_forces_ns", "forward_dynamics_ns",
        "jacobian_ns", "forward_kinematics_ns", "centroidal_momentum_matrix_ns"}) {
    EXPECT_TRUE(bench.contains(key)) << key;
    EXPECT_GT(bench[key].get<double>(), 0.0) << key;
  }
  EXPECT_EQ(run({"--help"}).find("usage"), 0u);
  EXPECT_NE(run({"eval", "--help"}).find("--state"), std::string::npos);
}

TEST(Cli, BadInput) {
  const std::string pendulum = wbi::test::project_model("pendulum.urdf").string();
  auto error_of = [](const std::vector<std::string>& args) -> std::string {
    try {
      run(args);
    } catch (const wbi::cli::UsageError& e) {
      return std::string("usage: ") + e.what();
    } catch (const std::exception& e) {
      return e.what();
    }
    return "no error";
  };
  {
    // No sub-verb: the usage, which lists them, and exit 1 (as every verb's sub-commands).
    std::ostringstream usage;
    std::streambuf* old = std::cout.rdbuf(usage.rdbuf());
    const int rc = wbi::cli::run_model({});
    std::cout.rdbuf(old);
    EXPECT_EQ(rc, 1);
    EXPECT_EQ(usage.str().find("usage: wbi model {info,eval,bench,mjcf}"), 0u) << usage.str();
  }
  EXPECT_NE(error_of({"frob"}).find("frob"), std::string::npos);
  EXPECT_NE(error_of({"info"}).find("usage: "), std::string::npos);
  EXPECT_NE(error_of({"info", "/no/such.urdf"}).find("/no/such.urdf"), std::string::npos);
  EXPECT_NE(error_of({"eval", pendulum}).find("usage: "), std::string::npos);  // --state missing
  EXPECT_NE(error_of({"eval", pendulum, "--state", write_state(json{{"q", {1, 2}}})}).find("'q'"),
            std::string::npos);
  EXPECT_NE(
      error_of({"eval", pendulum, "--state", write_state(json{{"frames", {"nope"}}})}).find("nope"),
      std::string::npos);
  EXPECT_NE(
      error_of({"eval", pendulum, "--state", write_state(json{{"joints", {"nope"}}})}).find("nope"),
      std::string::npos);
  EXPECT_NE(error_of({"eval", pendulum, "--state", write_state(json{{"qq", {1}}})})
                .find("unknown key 'qq'"),
            std::string::npos);
  EXPECT_NE(error_of({"eval", pendulum, "--state", write_state(json{{"base_position", {0, 0, 0}}})})
                .find("fixed base"),
            std::string::npos);
  EXPECT_NE(error_of({"eval", pendulum, "--joints", "nope", "--state", write_state(json::object())})
                .find("nope"),
            std::string::npos);
  if (std::filesystem::exists(humanoid())) {
    EXPECT_NE(error_of({"eval", humanoid(), "--state",
                        write_state(json{{"base_quaternion", {0, 0, 0, 0}}})})
                  .find("unit quaternion"),
              std::string::npos);
    EXPECT_NE(
        error_of({"eval", humanoid(), "--state", write_state(json{{"base_velocity", {0, 0}}})})
            .find("6"),
        std::string::npos);
  }
}

TEST(Cli, Armature) {
  const std::string pendulum = wbi::test::project_model("double_pendulum.urdf").string();
  const json info = json::parse(run({"info", pendulum, "--armature", "joint2=0.25", "--json"}));
  EXPECT_EQ(info["joints"][0]["armature"].get<double>(), 0.0);
  EXPECT_EQ(info["joints"][1]["armature"].get<double>(), 0.25);
  const std::string text = run({"info", pendulum, "--armature", "joint1=0.5,joint2=0.25"});
  EXPECT_NE(text.find("armature 0.5"), std::string::npos) << text;
  EXPECT_NE(text.find("armature 0.25"), std::string::npos) << text;
  EXPECT_NE(run({"info", "--help"}).find("--armature"), std::string::npos);
  // eval: M gains exactly the armature on the diagonal
  const std::string state = write_state(json{{"q", {0.1, 0.2}}});
  const Eigen::MatrixXd M0 =
      matrix(json::parse(run({"eval", pendulum, "--state", state}))["mass_matrix"]);
  const Eigen::MatrixXd M =
      matrix(json::parse(run({"eval", pendulum, "--state", state, "--armature",
                              "joint1=0.5,joint2=0.25"}))["mass_matrix"]);
  Eigen::MatrixXd expected = M0;
  expected(0, 0) += 0.5;
  expected(1, 1) += 0.25;
  EXPECT_EQ(M, expected);
  // bad lists: usage errors naming the entry; bad values: the loader's error naming the joint
  auto error_of = [&](const std::string& list) -> std::string {
    try {
      run({"info", pendulum, "--armature", list});
    } catch (const std::exception& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error_of("joint1").find("'joint1' is not JOINT=VALUE"), std::string::npos);
  EXPECT_NE(error_of("joint1=heavy").find("'joint1' is not a number"), std::string::npos);
  EXPECT_NE(error_of("joint1=1,joint1=2").find("given twice"), std::string::npos);
  EXPECT_NE(error_of("elbow=1").find("unknown joint 'elbow'"), std::string::npos);
  EXPECT_NE(error_of("joint2=-1").find("armature of joint 'joint2' is -1"), std::string::npos);
}
