// Momentum-based balancing as a component (type "momentum_balance"): the
// controller of momentum_balance.hpp connected through the DDS whole-body
// interface (local model), run by the component runtime. One control tick per
// new state estimate; the CoM reference is a sinusoid in the robot's time.
//
// Parameters:
//   robot              required; the robot's name
//   urdf               required; the robot's URDF (local model), relative to the host file
//   model_backend      the dynamics library of the local model: wbi (default) or dart
//                      (when built with DART; model_service/README.md)
//   joints             required; the controlled joints (torque mode). The robot's other
//                      joints are left as they are (sim_robot holds them in position
//                      mode) and the model treats them as locked.
//   posture            postural reference, one per controlled joint [rad]
//                      (default: the posture measured at start)
//   com_amplitude      sinusoid amplitude [m] (default 0.05)
//   com_frequency_hz   (default 0.2)
//   com_direction      [x, y, z] in the world (default [0, 1, 0]: lateral)
//   settle_s           settling time before the sinusoid; meanwhile the reference is the
//                      measured CoM (default 0.5 s)
//   com_kp, com_kd, angular_momentum_kd, posture_bandwidth_hz, friction,
//   torsional_friction, min_normal_force, torque_weight, wrench_weight, foot_moment_weight,
//   foot_x_min, foot_x_max, foot_y_min, foot_y_max, left_sole, right_sole
//                      the controller's parameters (momentum_balance.hpp for defaults)
//   controller         name on the commands (default: the instance name)
//   max_age_s          oldest state accepted (default 0.05 s)
//   init_timeout_s     wait for the robot's components (default 30 s)
//   progress_period_s  a progress line every so often, robot time (default 1 s; 0: none)
//   signals            publish wbi/<robot>/signals/<instance> (wbi::msg::Signals) every
//                      tick: com_x/y/z, com_ref_x/y/z, com_error [m], left_f_z,
//                      right_f_z [N] (default true; false: none)
//   exit_after_s       > 0: after this robot time, end the hosting process
//                      (runtime::request_process_exit: under wbi_host a clean shutdown
//                      with the summary, exit code 0), so that a deploy file with
//                      shutdown_on_exit ends the launch (default 0: run until stopped)
// At shutdown it prints the stale cycles, QP failures, the largest CoM error
// and, last, "com tracking rms: X m" (from the start of the sinusoid).
#pragma once

#include "wbi/runtime/registry.hpp"

namespace wbi::controllers {

void register_momentum_balance(runtime::Registry& registry);

}  // namespace wbi::controllers
