// PD + gravity as a component (type "pd_gravity"): the controller of
// pd_gravity.hpp, connected through the DDS whole-body interface, run by the
// component runtime at its rate (default 1 kHz in the deploy files).
//
// Parameters:
//   robot            required; the robot's name
//   urdf             required; the robot's URDF (local model), relative to the host file
//   joints           required; the controlled joints, by name
//   target           q_d, one per controlled joint [rad]
//   bandwidth_hz     gains from the mass-matrix diagonal at q_d: kp = ω² M_jj, kd = 2ω M_jj
//                    (critically damped), ω = 2π bandwidth (default 5 Hz); or
//   kp, kd           explicit gains, one per joint (both or neither)
//   controller       name on the commands (default: the instance name)
//   max_age_s        oldest state accepted (default 0.05 s)
//   init_timeout_s   wait for the robot's components (default 30 s)
//   progress_period_s  a progress line every so often (default 1 s; 0: none)
// At shutdown it prints "final max joint error: X rad".
#pragma once

#include "wbi/runtime/registry.hpp"

namespace wbi::controllers {

void register_components(runtime::Registry& registry);

}  // namespace wbi::controllers
