// `wbi model eval|bench --backend wbi|dart` (cli/src/verbs/model.cpp), in-process:
// eval answers the same with both backends, bench names the backend, an unknown
// backend is a usage error naming the available ones.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "backend_test_common.hpp"
#include "options.hpp"
#include "verb.hpp"

namespace wbi::cli {
int run_model(Args args);
}

namespace {

using nlohmann::json;

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

// max |a − b| ≤ tol · max(1, max |b|) over the numbers of two JSON values of one shape.
double max_difference(const json& a, const json& b, double& scale) {
  if (a.is_number()) {
    scale = std::max(scale, std::abs(b.get<double>()));
    return std::abs(a.get<double>() - b.get<double>());
  }
  double worst = 0.0;
  if (a.is_array()) {
    EXPECT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
      worst = std::max(worst, max_difference(a[i], b[i], scale));
    }
  } else if (a.is_object()) {
    for (const auto& [key, value] : a.items()) {
      EXPECT_TRUE(b.contains(key)) << key;
      if (b.contains(key)) {
        worst = std::max(worst, max_difference(value, b[key], scale));
      }
    }
  }
  return worst;
}

TEST(ModelCliBackend, EvalAgreesBetweenBackends) {
  if (!wbi::test::dart_built()) {
    GTEST_SKIP() << wbi::test::kDartMissing;
  }
  const std::string urdf = wbi::test::project_model("humanoid.urdf").string();
  const auto model = wbi::model::load_urdf_file(urdf);
  std::mt19937 rng(3);
  const Eigen::VectorXd q = wbi::model::random_configuration(model, rng);
  json state;
  state["q"] = std::vector<double>(q.data() + 7, q.data() + q.size());
  state["dq"] = std::vector<double>(static_cast<std::size_t>(model.n_joints), 0.4);
  state["base_position"] = {0.1, -0.2, 0.9};
  state["base_quaternion"] = {q[3], q[4], q[5], q[6]};
  state["base_velocity"] = {0.1, 0.2, -0.3, 0.5, -0.4, 0.2};
  state["frames"] = {"l_sole", "r_hand"};
  const auto path = std::filesystem::temp_directory_path() / "wbi_model_backend_cli_state.json";
  std::ofstream(path) << state.dump();
  const json wbi = json::parse(run({"eval", urdf, "--state", path.string()}));
  const json dart = json::parse(run({"eval", urdf, "--state", path.string(), "--backend", "dart"}));
  EXPECT_EQ(wbi["backend"], "wbi");
  EXPECT_EQ(dart["backend"], "dart");
  for (const char* key :
       {"mass_matrix", "bias_forces", "gravity_forces", "com", "centroidal_momentum", "frames"}) {
    double scale = 1.0;
    const double difference = max_difference(dart[key], wbi[key], scale);
    EXPECT_LE(difference, 1e-9 * scale) << key;
  }
  EXPECT_EQ(dart["frames"].size(), 2u);
}

TEST(ModelCliBackend, BenchNamesTheBackend) {
  const std::string urdf = wbi::test::project_model("arm7.urdf").string();
  for (const auto& name : wbi::model::model_backend_names()) {
    const json out = json::parse(
        run({"bench", urdf, "--json", "--states", "3", "--batch", "2", "--backend", name}));
    EXPECT_EQ(out["backend"], name);
    for (const char* key :
         {"mass_matrix_ns", "bias_forces_ns", "inverse_dynamics_ns", "forward_dynamics_ns",
          "jacobian_ns", "forward_kinematics_ns", "centroidal_momentum_matrix_ns"}) {
      EXPECT_GT(out[key].get<double>(), 0.0) << name << " " << key;
    }
  }
}

TEST(ModelCliBackend, UnknownBackendIsAUsageError) {
  const std::string urdf = wbi::test::project_model("arm7.urdf").string();
  try {
    run({"bench", urdf, "--backend", "pinocchio"});
    FAIL() << "no error";
  } catch (const wbi::cli::UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("'pinocchio'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--backend: unknown model backend"), std::string::npos)
        << e.what();
    // The registry's one wording for an unknown name: the known ones, sorted.
    EXPECT_NE(std::string(e.what()).find("(known: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("wbi)"), std::string::npos) << e.what();
  }
}

}  // namespace
