// How a simulation integrates the dynamics: the one integrator enum of the
// robot config (mujoco.integrator) and the MJCF writer, spelt and ordered as
// MuJoCo 2.2 spells and numbers them (mjtIntegrator, the XML's `integrator`).
#pragma once

#include <cstdint>

#include "wbi/vocabulary/enum_names.hpp"

namespace wbi {

enum class Integrator : std::uint8_t {
  euler,     // semi-implicit Euler
  rk4,       // 4th-order Runge-Kutta
  implicit,  // implicit in the velocity-dependent forces (damping)
};

template <>
struct EnumNames<Integrator> {
  static constexpr std::array names{"Euler", "RK4", "implicit"};
};

constexpr const char* to_string(Integrator integrator) { return enum_name(integrator); }

}  // namespace wbi
