// Argument checks at the entry points: messages name the argument and the expected size.
#pragma once

#include <stdexcept>
#include <string>

#include "wbi/model/data.hpp"

namespace wbi::model::detail {

[[noreturn]] void throw_size(const char* function, const char* argument, long expected, long got);
[[noreturn]] void throw_frame(const Model& model, int frame);
[[noreturn]] void throw_data(const Model& model);
[[noreturn]] void throw_singular(const Model& model, int body);

// A Data must come from this model (same sizes).
inline void check_data(const Model& model, const Data& data) {
  if (static_cast<int>(data.R_WB.size()) != model.n_bodies || data.M.rows() != model.nv) {
    throw_data(model);
  }
}

inline void check_size(const char* function, const char* argument, const ConstVectorRef& x,
                       int expected) {
  if (x.size() != expected) {
    throw_size(function, argument, expected, static_cast<long>(x.size()));
  }
}

inline void check_frame(const Model& model, int frame) {
  if (frame < 0 || frame >= model.n_frames()) {
    throw_frame(model, frame);
  }
}

// S_B ν_B for the mixed base velocity (ṗ_B, ω_B): (ṗ_B + p_B × ω_B, ω_B) at the world origin.
inline Vector6d base_motion(const Vector3d& p_B, const Vector6d& nu_B) {
  return join(nu_B.head<3>() + p_B.cross(nu_B.tail<3>()), nu_B.tail<3>());
}

// S_Bᵀ f: a world-origin force as (force, moment about p_B).
inline Vector6d base_force(const Vector3d& p_B, const Vector6d& f) {
  return force_at_point(f, p_B);
}

}  // namespace wbi::model::detail
