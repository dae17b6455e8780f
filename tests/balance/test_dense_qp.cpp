// wbi::qp::DenseQp against problems with known solutions, degenerate and
// infeasible ones, repeated solves (no allocation), and the KKT conditions of
// random problems.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Dense>
#include <wbi/qp/dense_qp.hpp>

#include "allocation_counter.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using wbi::qp::DenseQp;
using wbi::qp::Status;

// No constraints of a kind: a 0-row matrix of the right width.
MatrixXd none(int n) { return MatrixXd(0, n); }

TEST(DenseQp, UnconstrainedMinimum) {
  DenseQp qp(2, 0, 0);
  const MatrixXd H = Eigen::Vector2d(2.0, 4.0).asDiagonal();
  ASSERT_EQ(qp.solve(H, Eigen::Vector2d(-2.0, -4.0), none(2), VectorXd(0), none(2), VectorXd(0)),
            Status::optimal);
  EXPECT_TRUE(qp.solution().isApprox(Eigen::Vector2d(1.0, 1.0), 1e-12));
  EXPECT_NEAR(qp.objective(), -3.0, 1e-12);
  EXPECT_EQ(qp.active_inequalities(), 0);
}

TEST(DenseQp, EqualityOnly) {
  // min ½‖x‖²  s.t.  x₁ + x₂ = 1  →  x = (½, ½), λ = ½
  DenseQp qp(2, 1, 0);
  MatrixXd A(1, 2);
  A << 1.0, 1.0;
  ASSERT_EQ(qp.solve(MatrixXd::Identity(2, 2), VectorXd::Zero(2), A, VectorXd::Ones(1), none(2),
                     VectorXd(0)),
            Status::optimal);
  EXPECT_TRUE(qp.solution().isApprox(Eigen::Vector2d(0.5, 0.5), 1e-12));
  EXPECT_NEAR(qp.equality_multipliers()[0], 0.5, 1e-12);
}

TEST(DenseQp, ActiveAndInactiveInequalities) {
  // min ½‖x − (2, 2)‖²  s.t.  x₁ ≤ 1, x₂ ≤ ½, x₁ ≥ −5  →  x = (1, ½), λ = (1, 3/2, 0)
  DenseQp qp(2, 0, 3);
  MatrixXd C(3, 2);
  C << -1.0, 0.0, 0.0, -1.0, 1.0, 0.0;
  const Eigen::Vector3d d(-1.0, -0.5, -5.0);
  ASSERT_EQ(
      qp.solve(MatrixXd::Identity(2, 2), Eigen::Vector2d(-2.0, -2.0), none(2), VectorXd(0), C, d),
      Status::optimal);
  EXPECT_TRUE(qp.solution().isApprox(Eigen::Vector2d(1.0, 0.5), 1e-12));
  EXPECT_TRUE(qp.inequality_multipliers().isApprox(Eigen::Vector3d(1.0, 1.5, 0.0), 1e-12));
  EXPECT_EQ(qp.active_inequalities(), 2);
}

TEST(DenseQp, ConstraintDroppedOnTheWay) {
  // min ½‖x‖² − x₁ − x₂ with x₁ + x₂ ≤ 1 and x₁ ≥ 0.8: the unconstrained minimum (1, 1)
  // violates the sum most; adding it alone gives (½, ½), which violates x₁ ≥ 0.8.
  DenseQp qp(2, 0, 2);
  MatrixXd C(2, 2);
  C << -1.0, -1.0, 1.0, 0.0;
  ASSERT_EQ(qp.solve(MatrixXd::Identity(2, 2), Eigen::Vector2d(-1.0, -1.0), none(2), VectorXd(0), C,
                     Eigen::Vector2d(-1.0, 0.8)),
            Status::optimal);
  EXPECT_TRUE(qp.solution().isApprox(Eigen::Vector2d(0.8, 0.2), 1e-12));
  // Stationarity: x − (1, 1) = Cᵀλ  →  λ_sum = 0.8, λ_x1 = 0.6
  EXPECT_TRUE(qp.inequality_multipliers().isApprox(Eigen::Vector2d(0.8, 0.6), 1e-12));
}

TEST(DenseQp, RedundantAndDegenerateConstraints) {
  // The same inequality three times (once scaled), and three lines through the optimum in 2D.
  DenseQp qp(2, 2, 6);
  MatrixXd A(2, 2);
  A << 1.0, 1.0, 2.0, 2.0;  // x₁ + x₂ = 1 twice
  MatrixXd C(6, 2);
  C << -1.0, 0.0,  // x₁ ≤ 0.25
      -1.0, 0.0,   //
      -2.0, 0.0,   //
      0.0, 1.0,    // x₂ ≥ 0.75   (through (0.25, 0.75) as well)
      -1.0, -1.0,  // x₁ + x₂ ≤ 1  (the equality again)
      1.0, -1.0;   // x₁ − x₂ ≥ −0.5 (through the optimum)
  VectorXd d(6);
  d << -0.25, -0.25, -0.5, 0.75, -1.0, -0.5;
  ASSERT_EQ(qp.solve(MatrixXd::Identity(2, 2), Eigen::Vector2d(-1.0, 0.0), A, Eigen::Vector2d(1, 2),
                     C, d),
            Status::optimal);
  EXPECT_TRUE(qp.solution().isApprox(Eigen::Vector2d(0.25, 0.75), 1e-10));
  const VectorXd s = C * qp.solution() - d;
  EXPECT_GE(s.minCoeff(), -1e-10);
  EXPECT_GE(qp.inequality_multipliers().minCoeff(), 0.0);
}

TEST(DenseQp, ReportsInfeasibility) {
  DenseQp bounds(1, 0, 2);  // x ≥ 1 and x ≤ 0
  MatrixXd C(2, 1);
  C << 1.0, -1.0;
  EXPECT_EQ(bounds.solve(MatrixXd::Identity(1, 1), VectorXd::Zero(1), none(1), VectorXd(0), C,
                         Eigen::Vector2d(1.0, 0.0)),
            Status::infeasible);

  DenseQp equalities(2, 2, 0);  // x₁ = 0 and x₁ = 1
  MatrixXd A(2, 2);
  A << 1.0, 0.0, 1.0, 0.0;
  EXPECT_EQ(equalities.solve(MatrixXd::Identity(2, 2), VectorXd::Zero(2), A,
                             Eigen::Vector2d(0.0, 1.0), none(2), VectorXd(0)),
            Status::infeasible);

  DenseQp empty_row(2, 0, 1);  // 0 ≥ 1
  EXPECT_EQ(empty_row.solve(MatrixXd::Identity(2, 2), VectorXd::Zero(2), none(2), VectorXd(0),
                            MatrixXd::Zero(1, 2), VectorXd::Ones(1)),
            Status::infeasible);

  DenseQp with_equality(2, 1, 1);  // x₁ + x₂ = 1 and x₁ + x₂ ≥ 2
  MatrixXd E(1, 2);
  E << 1.0, 1.0;
  EXPECT_EQ(with_equality.solve(MatrixXd::Identity(2, 2), VectorXd::Zero(2), E, VectorXd::Ones(1),
                                E, 2.0 * VectorXd::Ones(1)),
            Status::infeasible);
}

TEST(DenseQp, RejectsIndefiniteHessianAndWrongSizes) {
  DenseQp qp(2, 0, 0);
  const MatrixXd H = Eigen::Vector2d(1.0, -1.0).asDiagonal();
  EXPECT_EQ(qp.solve(H, VectorXd::Zero(2), none(2), VectorXd(0), none(2), VectorXd(0)),
            Status::not_positive_definite);
  EXPECT_EQ(wbi::qp::to_string(Status::not_positive_definite), "H not positive definite");
  try {
    qp.solve(MatrixXd::Identity(3, 3), VectorXd::Zero(2), none(2), VectorXd(0), none(2),
             VectorXd(0));
    FAIL() << "no error for a 3x3 H";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("H is 3x3, expected 2x2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(DenseQp(0, 0, 0), std::invalid_argument);
}

// A random strictly convex problem of the balancing QP's size with a known feasible point.
struct RandomProblem {
  MatrixXd H, A, C;
  VectorXd g, b, d;
};

RandomProblem random_problem(std::mt19937_64& rng, int n, int m_eq, int m_in) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto random_matrix = [&](int rows, int cols) {
    return MatrixXd(MatrixXd::NullaryExpr(rows, cols, [&] { return normal(rng); }));
  };
  RandomProblem p;
  const MatrixXd B = random_matrix(n, n);
  p.H = B * B.transpose() + 0.1 * MatrixXd::Identity(n, n);
  p.g = 10.0 * random_matrix(n, 1);
  p.A = random_matrix(m_eq, n);
  p.C = random_matrix(m_in, n);
  const VectorXd feasible = random_matrix(n, 1);
  p.b = p.A * feasible;
  // Half of the inequalities tight at the feasible point: many end up active.
  p.d = p.C * feasible - VectorXd(VectorXd::NullaryExpr(
                             m_in, [&] { return uniform(rng) < 0.5 ? 0.0 : uniform(rng); }));
  return p;
}

TEST(DenseQp, RandomProblemsSatisfyKkt) {
  std::mt19937_64 rng(7);
  constexpr int n = 12, m_eq = 2, m_in = 30;
  DenseQp qp(n, m_eq, m_in);
  int with_active = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const RandomProblem p = random_problem(rng, n, m_eq, m_in);
    ASSERT_EQ(qp.solve(p.H, p.g, p.A, p.b, p.C, p.d), Status::optimal) << "trial " << trial;
    const VectorXd& x = qp.solution();
    const VectorXd slack = p.C * x - p.d;
    const VectorXd& lambda = qp.inequality_multipliers();
    const double scale = 1.0 + p.g.norm();
    EXPECT_LT((p.A * x - p.b).norm(), 1e-9 * scale) << "trial " << trial;
    EXPECT_GT(slack.minCoeff(), -1e-9 * scale) << "trial " << trial;
    EXPECT_GE(lambda.minCoeff(), 0.0) << "trial " << trial;
    EXPECT_LT(lambda.cwiseProduct(slack).cwiseAbs().maxCoeff(), 1e-8 * scale) << "trial " << trial;
    const VectorXd stationarity =
        p.H * x + p.g - p.A.transpose() * qp.equality_multipliers() - p.C.transpose() * lambda;
    EXPECT_LT(stationarity.norm(), 1e-8 * scale) << "trial " << trial;
    with_active += qp.active_inequalities() > 0 ? 1 : 0;
  }
  EXPECT_GT(with_active, 250);  // the test exercised the active set, not only free minima
}

TEST(DenseQp, RepeatedSolvesAreIdenticalAndAllocateNothing) {
  std::mt19937_64 rng(11);
  const RandomProblem first = random_problem(rng, 12, 0, 24);
  const RandomProblem second = random_problem(rng, 12, 0, 24);
  DenseQp qp(12, 0, 24);
  ASSERT_EQ(qp.solve(first.H, first.g, first.A, first.b, first.C, first.d), Status::optimal);
  const VectorXd x_first = qp.solution();
  ASSERT_EQ(qp.solve(second.H, second.g, second.A, second.b, second.C, second.d), Status::optimal);
  const VectorXd x_second = qp.solution();
  const long before = wbi::test::allocation_count();
  bool same = true;
  for (int k = 0; k < 50; ++k) {
    const RandomProblem& p = k % 2 == 0 ? first : second;
    qp.solve(p.H, p.g, p.A, p.b, p.C, p.d);
    same = same && qp.solution() == (k % 2 == 0 ? x_first : x_second);
  }
  EXPECT_EQ(wbi::test::allocation_count() - before, 0);
  EXPECT_TRUE(same);
}

TEST(DenseQp, MaxIterationsIsReported) {
  std::mt19937_64 rng(3);
  const RandomProblem p = random_problem(rng, 12, 0, 30);
  DenseQp qp(12, 0, 30, 1);
  EXPECT_EQ(qp.solve(p.H, p.g, p.A, p.b, p.C, p.d), Status::max_iterations);
}

}  // namespace
