// One update of each base estimator for the project humanoid (30 joints), with
// the joints moving a little from sample to sample as a standing robot's do.
#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <vector>

#include <wbi/estimator/base_estimator.hpp>
#include <wbi/estimator/legged_base_estimator.hpp>
#include <wbi/model/urdf.hpp>

namespace {

const std::string kUrdf = std::string(WBI_PROJECT_MODELS_DIR) + "/humanoid.urdf";

std::vector<std::string> humanoid_joints() {
  const auto model = wbi::model::load_urdf_file(kUrdf);
  return {model.joint_name.begin(), model.joint_name.end()};
}

// The joint state of sample k: knees bent, every joint oscillating by a few mrad.
void joint_state(std::int64_t k, Eigen::VectorXd& q, Eigen::VectorXd& dq) {
  for (Eigen::Index j = 0; j < q.size(); ++j) {
    const double phase = 1e-3 * static_cast<double>(k) + 0.1 * static_cast<double>(j);
    q[j] = 0.003 * std::sin(phase);
    dq[j] = 0.003 * std::cos(phase);
  }
}

void BM_LeggedBaseEstimator(benchmark::State& state) {
  const auto joints = humanoid_joints();
  wbi::estimator::LeggedBaseOptions options;
  options.force_frames = {{{"l_foot"}, {"r_foot"}}};
  wbi::estimator::LeggedBaseEstimator estimator(kUrdf, joints, options);
  const auto n = static_cast<Eigen::Index>(joints.size());
  Eigen::VectorXd q(n), dq(n), ddq = Eigen::VectorXd::Zero(n);
  wbi::estimator::ImuInput imu;
  imu.accelerometer << 0.0, 0.0, 9.81;
  Eigen::Matrix<double, 3, 2> forces;
  forces << 0.0, 0.0, 0.0, 0.0, 160.0, 160.0;
  std::int64_t k = 0;
  for (auto _ : state) {
    joint_state(k, q, dq);
    benchmark::DoNotOptimize(estimator.update(k * 1'000'000, q, dq, ddq, imu, forces));
    ++k;
  }
}
BENCHMARK(BM_LeggedBaseEstimator)->Unit(benchmark::kMicrosecond);

void BM_FixedLinkBaseEstimator(benchmark::State& state) {
  const auto joints = humanoid_joints();
  wbi::estimator::FixedLinkBaseEstimator estimator(kUrdf, joints, "l_sole",
                                                   Eigen::Matrix4d::Identity());
  const auto n = static_cast<Eigen::Index>(joints.size());
  Eigen::VectorXd q(n), dq(n), ddq = Eigen::VectorXd::Zero(n);
  std::int64_t k = 0;
  for (auto _ : state) {
    joint_state(k, q, dq);
    benchmark::DoNotOptimize(estimator.update(q, dq, ddq));
    ++k;
  }
}
BENCHMARK(BM_FixedLinkBaseEstimator)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
