// Cost of one tick of the F/T-based estimator of joint torques and external
// wrenches (estimation/wrenches): iCub 3 (../shared/models/iCubGenova09, 32
// joints, 8 F/T sensors, 9 hypotheses) and the project's humanoid (2
// sensors, 3 hypotheses; "humanoid_shared" puts 3 hypotheses on one submodel,
// the least-squares path). Target (issue 38): ≤ 50 µs per tick on iCub 3.
// Also the model's accelerations from commanded torques (model_accelerations.hpp)
// with both feet held and friction on every joint, at rest (every joint may
// stick: the largest constraint system) and moving (none sticks).
// Run: build/bin/wbi_bench_wrench_estimation --benchmark_format=json
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "wbi/estimation/model_accelerations.hpp"
#include "wbi/estimation/wrench_estimator.hpp"
#include "wbi/model/configuration.hpp"
#include "wbi/model/urdf.hpp"

namespace {

using wbi::estimation::WrenchEstimatorOptions;
using wbi::model::Vector6d;

const std::filesystem::path kSource(WBI_SOURCE_DIR);

WrenchEstimatorOptions icub3_options() {
  WrenchEstimatorOptions o;
  for (const std::string s : {"l", "r"}) {
    for (const char* part : {"leg", "foot_front", "foot_rear", "arm"}) {
      o.sensors.push_back({s + "_" + part + "_ft", s + "_" + part + "_ft_sensor"});
    }
    o.contact_links.insert(o.contact_links.end(), {s + "_foot_front", s + "_foot_rear"});
    o.extra_links.insert(o.extra_links.end(), {s + "_lower_leg", s + "_hand"});
  }
  o.extra_links.push_back("chest");
  return o;
}

WrenchEstimatorOptions humanoid_options(bool shared) {
  WrenchEstimatorOptions o;
  o.sensors = {{"l_foot_ft", "l_foot_ft_sensor"}, {"r_foot_ft", "r_foot_ft_sensor"}};
  o.contact_links = {"l_sole", "r_sole"};
  o.extra_links = {"chest"};
  if (shared) {
    o.extra_links.insert(o.extra_links.end(), {"l_hand", "r_hand"});
  }
  return o;
}

void update(benchmark::State& state, const std::filesystem::path& urdf,
            const WrenchEstimatorOptions& options) {
  if (!std::filesystem::exists(urdf)) {
    state.SkipWithError(("skipped: " + urdf.string() + " not found").c_str());
    return;
  }
  const wbi::model::Model model = wbi::model::load_urdf_file(urdf.string());
  wbi::estimation::WrenchEstimator estimator(model, options);
  constexpr int kStates = 64;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<Eigen::VectorXd> q, nu, dnu;
  std::vector<std::vector<Vector6d>> readings;
  for (int i = 0; i < kStates; ++i) {
    q.push_back(wbi::model::random_configuration(model, rng));
    nu.push_back(Eigen::VectorXd::NullaryExpr(model.nv, [&] { return d(rng); }));
    dnu.push_back(Eigen::VectorXd::NullaryExpr(model.nv, [&] { return d(rng); }));
    readings.emplace_back();
    for (std::size_t s = 0; s < options.sensors.size(); ++s) {
      readings.back().push_back(Vector6d::NullaryExpr([&] { return 50.0 * d(rng); }));
    }
  }
  int i = 0;
  for (auto _ : state) {
    estimator.update(q[i], nu[i], dnu[i], readings[i]);
    benchmark::DoNotOptimize(estimator.joint_torques().data());
    i = (i + 1) % kStates;
  }
  state.counters["joints"] = model.n_joints;
  state.counters["sensors"] = static_cast<double>(options.sensors.size());
  state.counters["hypotheses"] = static_cast<double>(estimator.link_names().size());
}

void BM_WrenchEstimatorICub3(benchmark::State& state) {
  update(state, kSource.parent_path() / "shared/models/iCubGenova09/model.urdf", icub3_options());
}
void BM_WrenchEstimatorHumanoid(benchmark::State& state) {
  update(state, kSource / "models/humanoid.urdf", humanoid_options(false));
}
void BM_WrenchEstimatorHumanoidShared(benchmark::State& state) {
  update(state, kSource / "models/humanoid.urdf", humanoid_options(true));
}

// feet: the contact frames held; moving: every joint faster than the stick velocity.
void model_accelerations(benchmark::State& state, const std::filesystem::path& urdf,
                         const std::vector<std::string>& feet, bool moving) {
  if (!std::filesystem::exists(urdf)) {
    state.SkipWithError(("skipped: " + urdf.string() + " not found").c_str());
    return;
  }
  const wbi::model::Model model = wbi::model::load_urdf_file(urdf.string());
  std::vector<int> frames;
  for (const auto& foot : feet) {
    frames.push_back(model.frame_id(foot));
  }
  const Eigen::VectorXd friction = Eigen::VectorXd::Constant(model.n_joints, 1.0);
  wbi::estimation::ModelAccelerations accelerations(model, {0.5 * friction, friction}, frames);
  constexpr int kStates = 64;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<Eigen::VectorXd> q, nu, tau;
  for (int i = 0; i < kStates; ++i) {
    q.push_back(wbi::model::random_configuration(model, rng));
    nu.push_back(moving ? Eigen::VectorXd::Constant(model.nv, 0.5)
                        : Eigen::VectorXd::Zero(model.nv));
    tau.push_back(Eigen::VectorXd::NullaryExpr(model.n_joints, [&] { return 5.0 * d(rng); }));
  }
  const std::vector<char> held(frames.size(), 1);
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(accelerations.update(q[i], nu[i], tau[i], held).data());
    i = (i + 1) % kStates;
  }
  state.counters["joints"] = model.n_joints;
  state.counters["stuck"] = accelerations.stuck_joints();
}

void BM_ModelAccelerationsICub3AtRest(benchmark::State& state) {
  model_accelerations(state, kSource.parent_path() / "shared/models/iCubGenova09/model.urdf",
                      {"l_foot_front", "l_foot_rear", "r_foot_front", "r_foot_rear"}, false);
}
void BM_ModelAccelerationsICub3Moving(benchmark::State& state) {
  model_accelerations(state, kSource.parent_path() / "shared/models/iCubGenova09/model.urdf",
                      {"l_foot_front", "l_foot_rear", "r_foot_front", "r_foot_rear"}, true);
}
void BM_ModelAccelerationsHumanoidAtRest(benchmark::State& state) {
  model_accelerations(state, kSource / "models/humanoid.urdf", {"l_sole", "r_sole"}, false);
}

BENCHMARK(BM_ModelAccelerationsICub3AtRest)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ModelAccelerationsICub3Moving)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ModelAccelerationsHumanoidAtRest)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WrenchEstimatorICub3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WrenchEstimatorHumanoid)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WrenchEstimatorHumanoidShared)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
