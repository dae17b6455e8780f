// A small dense convex QP solver of the Goldfarb–Idnani dual active-set family
// (D. Goldfarb, A. Idnani, "A numerically stable dual method for solving
// strictly convex quadratic programs", Math. Programming 27, 1983):
//
//   minimize    ½ xᵀ H x + gᵀ x
//   subject to  A_eq x  = b_eq
//               C x    ≥ d
//
// H must be symmetric positive definite. The method starts at the
// unconstrained minimum, adds the equalities, then repeatedly adds the most
// violated inequality (dropping active ones whose multiplier would turn
// negative), so every iterate is dual feasible and the first primal feasible
// one is optimal. The workspace is sized at construction: solve() allocates
// nothing.
#pragma once

#include <string_view>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace wbi::qp {

enum class Status {
  optimal,
  infeasible,             // no x satisfies the constraints
  max_iterations,         // gave up; solution() is the last (dual-feasible) iterate
  not_positive_definite,  // H failed its Cholesky factorisation
};

std::string_view to_string(Status status);

class DenseQp {
 public:
  using ConstMatrixRef = Eigen::Ref<const Eigen::MatrixXd>;
  using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;

  // variables n, equalities m_eq, inequalities m_in (each may be 0 except n).
  // max_iterations ≤ 0: 3 (n + m_eq + m_in). Throws std::invalid_argument on
  // a negative size or n = 0.
  DenseQp(int variables, int equalities, int inequalities, int max_iterations = 0);

  // Sizes: H n×n, g n, A_eq m_eq×n, b_eq m_eq, C m_in×n, d m_in. Throws
  // std::invalid_argument naming a wrong size; never allocates.
  Status solve(const ConstMatrixRef& H, const ConstVectorRef& g, const ConstMatrixRef& A_eq,
               const ConstVectorRef& b_eq, const ConstMatrixRef& C, const ConstVectorRef& d);

  const Eigen::VectorXd& solution() const { return x_; }
  // Multipliers at the solution: Hx + g = A_eqᵀ λ_eq + Cᵀ λ_in, λ_in ≥ 0.
  const Eigen::VectorXd& equality_multipliers() const { return lambda_eq_; }
  const Eigen::VectorXd& inequality_multipliers() const { return lambda_in_; }
  double objective() const { return objective_; }
  int iterations() const { return iterations_; }
  int active_inequalities() const;  // at the solution
  Status status() const { return status_; }

  int variables() const { return n_; }
  int equalities() const { return m_eq_; }
  int inequalities() const { return m_in_; }

  // Constraint tolerance: an inequality counts as violated below −tolerance ·
  // max(1, |d_i|), row-normalised. Default 1e-10.
  void set_tolerance(double tolerance) { tolerance_ = tolerance; }

 private:
  // d = Jᵀ n_c; z = J₂ d₂ (primal step); r = R⁻¹ d₁ (dual step).
  void step_directions(int c);
  // Appends constraint c (d_ holds Jᵀ n_c) to the active set; false when it
  // depends linearly on the active ones.
  bool add_active(int c, double multiplier);
  // Removes the active constraint at position `position`.
  void drop_active(int position);
  // Adds the equalities; false when they are inconsistent.
  bool add_equalities();
  void finish(Status status);

  int n_, m_eq_, m_in_, max_iterations_;
  double tolerance_ = 1e-10;

  // Every constraint as a column normal n_c and right-hand side b_c (n_cᵀx ≥ or = b_c):
  // equalities first, then inequalities, copied once per solve.
  Eigen::MatrixXd normals_;
  Eigen::VectorXd rhs_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd J_;                  // L⁻ᵀ Q: its first q columns span the active normals
  Eigen::MatrixXd R_;                  // upper triangular, q×q used
  Eigen::VectorXd x_, d_, z_, r_, u_;  // u: multipliers of the active set
  Eigen::VectorXi active_;             // constraint index per active position
  Eigen::VectorXi is_active_;          // per constraint: 1 when active
  Eigen::VectorXd row_norm_;           // ‖n_c‖ per constraint
  Eigen::VectorXd lambda_eq_, lambda_in_;
  int q_ = 0;  // active constraints
  int iterations_ = 0;
  double objective_ = 0.0;
  Status status_ = Status::optimal;
};

}  // namespace wbi::qp
