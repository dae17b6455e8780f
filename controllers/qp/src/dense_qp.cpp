#include "wbi/qp/dense_qp.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace wbi::qp {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A constraint is linearly dependent on the active ones when the part of its
// normal outside their span is this small relative to the whole.
constexpr double kDependence = 1e-12;

void require(const char* what, Eigen::Index rows, Eigen::Index cols, int want_rows, int want_cols) {
  if (rows != want_rows || cols != want_cols) {
    throw std::invalid_argument("DenseQp::solve: " + std::string(what) + " is " +
                                std::to_string(rows) + "x" + std::to_string(cols) + ", expected " +
                                std::to_string(want_rows) + "x" + std::to_string(want_cols));
  }
}

// Rotates columns a and b of M by (c, s): a ← c a + s b, b ← −s a + c b.
template <typename Columns>
void rotate(Columns a, Columns b, double c, double s) {
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double ai = a[i];
    const double bi = b[i];
    a[i] = c * ai + s * bi;
    b[i] = -s * ai + c * bi;
  }
}

}  // namespace

std::string_view to_string(Status status) {
  switch (status) {
    case Status::optimal:
      return "optimal";
    case Status::infeasible:
      return "infeasible";
    case Status::max_iterations:
      return "max iterations";
    case Status::not_positive_definite:
      return "H not positive definite";
  }
  return "unknown";
}

DenseQp::DenseQp(int variables, int equalities, int inequalities, int max_iterations)
    : n_(variables),
      m_eq_(equalities),
      m_in_(inequalities),
      max_iterations_(max_iterations > 0 ? max_iterations
                                         : 3 * (variables + equalities + inequalities)),
      llt_(variables > 0 ? variables : 1) {
  if (variables <= 0 || equalities < 0 || inequalities < 0) {
    throw std::invalid_argument(
        "DenseQp: sizes must be variables > 0, equalities >= 0, "
        "inequalities >= 0 (got " +
        std::to_string(variables) + ", " + std::to_string(equalities) + ", " +
        std::to_string(inequalities) + ")");
  }
  const int m = m_eq_ + m_in_;
  normals_.setZero(n_, m);
  rhs_.setZero(m);
  J_.setZero(n_, n_);
  R_.setZero(n_, n_);
  x_.setZero(n_);
  d_.setZero(n_);
  z_.setZero(n_);
  r_.setZero(n_);
  u_.setZero(n_);
  active_.setZero(n_);
  is_active_.setZero(m);
  row_norm_.setZero(m);
  lambda_eq_.setZero(m_eq_);
  lambda_in_.setZero(m_in_);
  // Warm the factorisation's storage so that the first solve allocates nothing either.
  llt_.compute(Eigen::MatrixXd::Identity(n_, n_));
}

int DenseQp::active_inequalities() const {
  return static_cast<int>((lambda_in_.array() > 0).count());
}

void DenseQp::step_directions(int c) {
  d_.noalias() = J_.transpose() * normals_.col(c);
  const int free = n_ - q_;
  z_.noalias() = J_.rightCols(free) * d_.tail(free);
  if (q_ > 0) {
    r_.head(q_) = d_.head(q_);
    auto r_active = r_.head(q_);
    R_.topLeftCorner(q_, q_).triangularView<Eigen::Upper>().solveInPlace(r_active);
  }
}

bool DenseQp::add_active(int c, double multiplier) {
  // Givens rotations fold d's tail into d[q]: the first q + 1 columns of J then
  // span the active normals and n_c, and d's head is R's new column.
  for (int j = n_ - 1; j > q_; --j) {
    if (d_[j] == 0.0) {
      continue;
    }
    const double h = std::hypot(d_[j - 1], d_[j]);
    const double cos = d_[j - 1] / h;
    const double sin = d_[j] / h;
    d_[j - 1] = h;
    d_[j] = 0.0;
    rotate(J_.col(j - 1), J_.col(j), cos, sin);
  }
  if (std::abs(d_[q_]) <= kDependence * d_.norm()) {
    return false;
  }
  R_.col(q_).head(q_ + 1) = d_.head(q_ + 1);
  active_[q_] = c;
  u_[q_] = multiplier;
  is_active_[c] = 1;
  ++q_;
  return true;
}

void DenseQp::drop_active(int position) {
  is_active_[active_[position]] = 0;
  for (int j = position; j < q_ - 1; ++j) {
    active_[j] = active_[j + 1];
    u_[j] = u_[j + 1];
    R_.col(j).head(q_) = R_.col(j + 1).head(q_);
  }
  // R is upper Hessenberg from `position` on: rotate rows (and J's columns) back to triangular.
  for (int i = position; i < q_ - 1; ++i) {
    const double a = R_(i, i);
    const double b = R_(i + 1, i);
    if (b == 0.0) {
      continue;
    }
    const double h = std::hypot(a, b);
    const double cos = a / h;
    const double sin = b / h;
    for (int col = i; col < q_ - 1; ++col) {
      const double ri = R_(i, col);
      const double rn = R_(i + 1, col);
      R_(i, col) = cos * ri + sin * rn;
      R_(i + 1, col) = -sin * ri + cos * rn;
    }
    R_(i + 1, i) = 0.0;
    rotate(J_.col(i), J_.col(i + 1), cos, sin);
  }
  R_.col(q_ - 1).setZero();
  --q_;
}

bool DenseQp::add_equalities() {
  for (int c = 0; c < m_eq_; ++c) {
    step_directions(c);
    const double violation = normals_.col(c).dot(x_) - rhs_[c];
    const int free = n_ - q_;
    const double along = d_.tail(free).squaredNorm();  // = zᵀ n_c
    if (std::sqrt(along) <= kDependence * d_.norm() || along == 0.0) {
      // Redundant with the equalities already active: consistent or not.
      if (std::abs(violation) > tolerance_ * std::max(1.0, std::abs(rhs_[c]))) {
        return false;
      }
      continue;
    }
    const double t = -violation / along;
    x_ += t * z_;
    u_.head(q_) -= t * r_.head(q_);
    if (!add_active(c, t)) {
      return false;  // cannot happen after the test above; kept as a guard
    }
  }
  return true;
}

Status DenseQp::solve(const ConstMatrixRef& H, const ConstVectorRef& g, const ConstMatrixRef& A_eq,
                      const ConstVectorRef& b_eq, const ConstMatrixRef& C,
                      const ConstVectorRef& d) {
  require("H", H.rows(), H.cols(), n_, n_);
  require("g", g.rows(), g.cols(), n_, 1);
  require("A_eq", A_eq.rows(), A_eq.cols(), m_eq_, n_);
  require("b_eq", b_eq.rows(), b_eq.cols(), m_eq_, 1);
  require("C", C.rows(), C.cols(), m_in_, n_);
  require("d", d.rows(), d.cols(), m_in_, 1);

  normals_.leftCols(m_eq_) = A_eq.transpose();
  normals_.rightCols(m_in_) = C.transpose();
  rhs_.head(m_eq_) = b_eq;
  rhs_.tail(m_in_) = d;
  row_norm_ = normals_.colwise().norm().transpose();
  is_active_.setZero();
  u_.setZero();
  R_.setZero();
  q_ = 0;
  iterations_ = 0;
  lambda_eq_.setZero();
  lambda_in_.setZero();

  llt_.compute(H);
  if (llt_.info() != Eigen::Success) {
    x_.setZero();
    objective_ = kInfinity;
    return status_ = Status::not_positive_definite;
  }
  // J = L⁻ᵀ (so Jᵀ H J = I); the unconstrained minimum x = −H⁻¹ g = −J Jᵀ g.
  J_.setIdentity();
  llt_.matrixU().solveInPlace(J_);
  d_.noalias() = J_.transpose() * g;
  x_.noalias() = -J_ * d_;

  Status status = Status::optimal;
  if (!add_equalities()) {
    status = Status::infeasible;
  }
  while (status == Status::optimal) {
    // The most violated inequality, measured along its unit normal.
    int p = -1;
    double worst = 0.0;
    for (int i = 0; i < m_in_; ++i) {
      const int c = m_eq_ + i;
      if (is_active_[c] != 0) {
        continue;
      }
      const double slack = normals_.col(c).dot(x_) - rhs_[c];
      if (row_norm_[c] == 0.0) {
        if (slack < -tolerance_ * std::max(1.0, std::abs(rhs_[c]))) {
          p = -2;  // 0 ≥ d with d > 0
          break;
        }
        continue;
      }
      // Distance to the constraint's plane; violated beyond a tolerance relative to |d_i|.
      const double scaled = slack / row_norm_[c];
      const double limit = -tolerance_ * std::max(1.0, std::abs(rhs_[c]) / row_norm_[c]);
      if (scaled < limit && scaled < worst) {
        worst = scaled;
        p = c;
      }
    }
    if (p == -2) {
      status = Status::infeasible;
      break;
    }
    if (p < 0) {
      break;  // primal feasible: optimal
    }
    // Move towards satisfying p, dropping active inequalities that would get
    // negative multipliers, until p holds with equality.
    double u_p = 0.0;
    for (;;) {
      if (++iterations_ > max_iterations_) {
        status = Status::max_iterations;
        break;
      }
      step_directions(p);
      const int free = n_ - q_;
      const double along = d_.tail(free).squaredNorm();
      const bool blocked = std::sqrt(along) <= kDependence * d_.norm() || along == 0.0;
      const double full = blocked ? kInfinity : -(normals_.col(p).dot(x_) - rhs_[p]) / along;
      double partial = kInfinity;
      int drop = -1;
      for (int j = 0; j < q_; ++j) {
        if (active_[j] >= m_eq_ && r_[j] > 0.0 && u_[j] / r_[j] < partial) {
          partial = u_[j] / r_[j];
          drop = j;
        }
      }
      if (full == kInfinity && partial == kInfinity) {
        status = Status::infeasible;
        break;
      }
      const double t = std::min(full, partial);
      if (!blocked) {
        x_ += t * z_;
      }
      u_.head(q_) -= t * r_.head(q_);
      u_p += t;
      if (t == full) {
        if (!add_active(p, u_p)) {
          status = Status::infeasible;  // numerically dependent although z ≠ 0
        }
        break;
      }
      drop_active(drop);
    }
  }

  for (int j = 0; j < q_; ++j) {
    const int c = active_[j];
    if (c < m_eq_) {
      lambda_eq_[c] = u_[j];
    } else {
      lambda_in_[c - m_eq_] = u_[j];
    }
  }
  // ½ xᵀHx + gᵀx with H = L Lᵀ: ½‖Lᵀx‖² + gᵀx.
  z_.noalias() = llt_.matrixU() * x_;
  objective_ = 0.5 * z_.squaredNorm() + g.dot(x_);
  return status_ = status;
}

}  // namespace wbi::qp
