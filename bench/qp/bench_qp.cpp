// wbi::qp::DenseQp at the balancing controller's size: the feet wrenches of a
// humanoid on two feet (12 variables, 22 inequalities: per foot unilateral,
// friction pyramid, CoP rectangle, torsional friction), a cost that tracks a
// momentum rate, and larger random problems for scale.
//   build/bin/wbi_bench_qp --benchmark_format=json
#include <benchmark/benchmark.h>

#include <random>

#include <Eigen/Dense>
#include <wbi/qp/dense_qp.hpp>

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

struct Problem {
  MatrixXd H, A, C;
  VectorXd g, b, d;
};

// Two feet 0.14 m apart, CoM 0.45 m above and `lateral` m to the side:
// min ‖A f − ŵ‖² + 10⁻⁶‖f‖² with the contact constraints of each foot.
Problem balancing_problem(double lateral) {
  const double mu = 0.5 / std::sqrt(2.0), torsion = 0.01;
  const double x_min = -0.09, x_max = 0.09, y_min = -0.035, y_max = 0.035;
  Eigen::Matrix<double, 11, 6> foot;
  foot << 0, 0, 1, 0, 0, 0, -1, 0, mu, 0, 0, 0, 1, 0, mu, 0, 0, 0, 0, -1, mu, 0, 0, 0, 0, 1, mu, 0,
      0, 0, 0, 0, -x_min, 0, -1, 0, 0, 0, x_max, 0, 1, 0, 0, 0, -y_min, 1, 0, 0, 0, 0, y_max, -1, 0,
      0, 0, 0, torsion, 0, 0, -1, 0, 0, torsion, 0, 0, 1;
  Problem p;
  Eigen::Matrix<double, 6, 12> A = Eigen::Matrix<double, 6, 12>::Zero();
  const Eigen::Vector3d com(0.0, lateral, 0.45);
  const Eigen::Vector3d soles[2] = {{0.0, 0.07, 0.0}, {0.0, -0.07, 0.0}};
  p.C.setZero(22, 12);
  p.d.setZero(22);
  for (int i = 0; i < 2; ++i) {
    const Eigen::Vector3d r = soles[i] - com;
    Eigen::Matrix3d S;
    S << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    A.block<3, 3>(0, 6 * i).setIdentity();
    A.block<3, 3>(3, 6 * i) = S;
    A.block<3, 3>(3, 6 * i + 3).setIdentity();
    p.C.block<11, 6>(11 * i, 6 * i) = foot;
    p.d[11 * i] = 10.0;
  }
  Eigen::Matrix<double, 6, 1> target;
  target << 5.0, -20.0, 33.75 * 9.81, 0.5, -0.3, 0.1;
  p.H = A.transpose() * A + 1e-6 * MatrixXd::Identity(12, 12);
  p.g = -A.transpose() * target;
  p.A.setZero(0, 12);
  p.b.setZero(0);
  return p;
}

Problem random_problem(int n, int m) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  const auto random = [&](int r, int c) {
    return MatrixXd(MatrixXd::NullaryExpr(r, c, [&] { return normal(rng); }));
  };
  Problem p;
  const MatrixXd B = random(n, n);
  p.H = B * B.transpose() + 0.1 * MatrixXd::Identity(n, n);
  p.g = 10.0 * random(n, 1);
  p.C = random(m, n);
  p.d = p.C * random(n, 1);  // feasible, about half the constraints violated at the free minimum
  p.A.setZero(0, n);
  p.b.setZero(0);
  return p;
}

void solve_loop(benchmark::State& state, const Problem& p) {
  wbi::qp::DenseQp qp(static_cast<int>(p.H.rows()), 0, static_cast<int>(p.C.rows()));
  for (auto _ : state) {
    qp.solve(p.H, p.g, p.A, p.b, p.C, p.d);
    benchmark::DoNotOptimize(qp.solution().data());
  }
  state.counters["iterations"] = qp.iterations();
  state.counters["active"] = qp.active_inequalities();
  if (qp.status() != wbi::qp::Status::optimal) {
    state.SkipWithError("not optimal");
  }
}

// CoM centred, and 8 cm to the side (beyond the left foot's CoP limit: many constraints active).
void BM_BalancingWrenches(benchmark::State& state) {
  solve_loop(state, balancing_problem(0.01 * static_cast<double>(state.range(0))));
}
BENCHMARK(BM_BalancingWrenches)->Arg(0)->Arg(5)->Arg(8)->Unit(benchmark::kMicrosecond);

void BM_RandomDense(benchmark::State& state) {
  solve_loop(state,
             random_problem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1))));
}
BENCHMARK(BM_RandomDense)
    ->Args({12, 30})
    ->Args({42, 60})
    ->Args({72, 100})
    ->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
