// Body inertias in world coordinates (shared by several algorithms).
#pragma once

#include "wbi/model/data.hpp"

namespace wbi::model::detail {

// I_W[i] = body inertia in world axes about the world origin:
//   c = p_WB + R_WB c_B,  I_O = R I_c Rᵀ + m [c]×ᵀ[c]×.
// Pre: forward_kinematics current. Writes: I_W.
void world_inertias(const Model& model, Data& data);

// IA[i] = I_W[i] as a 6×6 matrix, the start of ABA's articulated inertias. Out of line
// so that forward_dynamics stays within GCC's inlining budget (the 6×6 fill in its
// loop was left out of line once the armature was added: 4 % more instructions).
// Pre: I_W current. Writes: IA.
void articulated_inertias(const Model& model, Data& data);

// I_C[i] = I_W[i] + Σ children I_C[c] (RBDA Table 6.2, first loop), the body inertias
// computed afresh (I_W is neither read nor written). Pre: forward_kinematics current.
// Writes: I_C.
void composite_inertias(const Model& model, Data& data);

// Mass and first moment only, straight from the poses: I_C[i].m, I_C[i].h
// (I_C[i].I untouched). Pre: forward_kinematics current. Writes: I_C (m, h).
void composite_mass_moments(const Model& model, Data& data);

}  // namespace wbi::model::detail
