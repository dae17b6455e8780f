// The simulated robot as DDS sees it (component type "sim_robot"): the
// simulation backend with the sensor side (description, sensor samples,
// ground truth, simulation clock) and the actuator side (commands and control
// parameters into the joint-level controller) in one loop, so that a tick is
//   read sensors → publish tick k → [lockstep: wait for every controller's
//   command for tick k] → apply commands → joint control → write → step.
//
// Parameters:
//   robot                 required; the robot's name (topics wbi/<robot>/…)
//   config                required; the robot config file (components/robot_config/README.md),
//                         relative to the host file
//   lockstep              false (default): real-time pacing; true: wait for commands
//   lockstep_controllers  names of the controllers (ActuatorCommand.controller) to wait for
//   lockstep_timeout_s    longest wait for a tick's commands (default 2 s; then a warning)
//   lockstep_start_timeout_s  longest wait for the first tick's commands, while the
//                         controllers start (default 60 s)
//   duration_s            stop stepping after this simulated time (default 0: never),
//                         printing "sim_robot 'NAME': duration_s D reached: stopped stepping"
//   watchdog_timeout_s    joint controller watchdog (default 0.1 s; 0 disables)
//   reference_speed       default POSITION-mode speed [rad/s] (default 0.5)
//   hold_at_start         true (default): every joint holds its initial position (POSITION
//                         mode) until commanded; false: joints start IDLE (unpowered)
//
// Status (wbi/status, counters and last_error): rejected_commands,
// rejected_parameters, watchdog_trips, limit_clamps (the actuator side, see
// src/actuator_side.hpp) and lockstep_timeouts; the last rejection or
// watchdog trip in words.
//
// The sensor side (src/sensor_side.hpp) and the actuator side
// (src/actuator_side.hpp) are the same parts a real robot's driver component
// uses (robot_driver.hpp); this component adds the simulation's stepping,
// ground truth, clock and lockstep around them.
// The loop runs on its own thread while ACTIVE (the simulation is the clock).
#pragma once

#include "wbi/runtime/registry.hpp"

namespace wbi::robot {

void register_components(runtime::Registry& registry);

}  // namespace wbi::robot
