#include "../inertias.hpp"

namespace wbi::model::detail {

namespace {

// The inertia of body i in world axes about the world origin, into I. Always inlined:
// with two callers, g++ without -march=native left it out of line, 3-4 % slower A_G
// and centroidal momentum than the loop it came from.
[[gnu::always_inline]] inline void world_inertia(const Model& model, const Data& data, int i,
                                                 SpatialInertia& I) {
  // c = p + R c_B;  I_O = R I_c Rᵀ + m [c]×ᵀ[c]×
  const double m = model.body_mass[i];
  const Matrix3d& R = data.R_WB[i];
  const Vector3d c = data.p_WB[i] + R * model.body_com[i];
  I.m = m;
  I.h = m * c;
  // R I_c Rᵀ, symmetric: T = R I_c, P = T Rᵀ as a whole product (vectorised by
  // columns; the 6 dots of rows of T and R were strided scalar code), then its upper
  // triangle mirrored so that I stays exactly symmetric
  Matrix3d T;
  T.noalias() = R * model.body_inertia_c[i];
  Matrix3d P;
  P.noalias() = T * R.transpose();
  const double cc = c.squaredNorm();
  for (int a = 0; a < 3; ++a) {
    for (int b = a; b < 3; ++b) {
      I.I(a, b) = I.I(b, a) = P(a, b) + m * ((a == b ? cc : 0.0) - c[a] * c[b]);
    }
  }
}

}  // namespace

void world_inertias(const Model& model, Data& data) {
  for (int i = 0; i < model.n_bodies; ++i) {
    world_inertia(model, data, i, data.I_W[i]);
  }
}

void articulated_inertias(const Model& model, Data& data) {
  for (int i = 0; i < model.n_bodies; ++i) {
    data.IA[i] = data.I_W[i].matrix();
  }
}

void composite_inertias(const Model& model, Data& data) {
  // I_C[i] = I_W[i] + Σ_children I_C[c], leaves to root. The body inertias go straight
  // into I_C (M and A_G need no I_W): a separate pass copying I_W was 5-18 % of M.
  for (int i = 0; i < model.n_bodies; ++i) {
    world_inertia(model, data, i, data.I_C[i]);
  }
  for (int i = model.n_bodies - 1; i > 0; --i) {
    data.I_C[model.parent[i]] += data.I_C[i];
  }
}

void composite_mass_moments(const Model& model, Data& data) {
  // m_C[i] = Σ_subtree m,  h_C[i] = Σ_subtree m c
  for (int i = 0; i < model.n_bodies; ++i) {
    const double m = model.body_mass[i];
    data.I_C[i].m = m;
    data.I_C[i].h = m * (data.p_WB[i] + data.R_WB[i] * model.body_com[i]);
  }
  for (int i = model.n_bodies - 1; i > 0; --i) {
    const int lambda = model.parent[i];
    data.I_C[lambda].m += data.I_C[i].m;
    data.I_C[lambda].h += data.I_C[i].h;
  }
}

}  // namespace wbi::model::detail
