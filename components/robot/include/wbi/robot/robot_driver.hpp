// The robot on DDS: one component, RobotDriver, runs any RobotBackend
// (wbi/actuation/robot_backend.hpp) with the sensor side (description, sensor
// samples) and the actuator side (commands and control parameters into the
// joint-level controller, watchdog, rejections on the status). One loop, every
// tick:
//   read → publish sensors (tick k) → [pace] → joint control → write → [step]
// Its pace is set by one of
//   the runner's period  a real robot: one tick per runner cycle (rate_hz, wall
//                        clock); register_driver;
//   lockstep             a simulation (SimulationBackend) that waits, at [pace],
//                        for every named controller's command for tick k, then
//                        steps: deterministic; register_simulation, lockstep: true;
//   real time            a simulation paced at real time (real_time: true, the
//                        default without lockstep; with lockstep: both waits);
//   none                 a simulation free running, as fast as it steps
//                        (lockstep: false, real_time: false).
// A simulation is its own clock: its loop runs on the driver's thread while
// ACTIVE (no rate_hz), stamps are simulation time, and it also publishes its
// ground truth (wbi/<robot>/ground_truth) and time (wbi/clock).
//
// A real robot:
//
//   wbi::robot::register_driver(registry, "my_robot", [](const runtime::Parameters& p) {
//     return std::make_unique<MyBackend>(p.require<std::string>("device"));
//   });
//
//   - name: robot
//     type: my_robot
//     rate_hz: 1000
//     parameters: {robot: my_robot, device: /dev/…}
//
// Parameters of every driver (besides the backend's own, which the factory reads):
//   robot               required; topics wbi/<robot>/…
//   watchdog_timeout_s  joint controller watchdog (default 0.1 s; 0 disables); also
//                       how long a silent claim owner keeps its joints from others
//   require_claims      false (default): a joint nobody claimed takes any sender's
//                       commands; true: only claimed joints are commanded (hardware)
//   reference_speed     default POSITION-mode speed [rad/s] (default 0.5)
//   hold_at_start       true (default): joints hold their position (POSITION mode)
//                       until commanded; false: they start IDLE (unpowered)
//   name_check_s        how long discovery runs before the robot takes its name
//                       (default 0.5 s; 0: no check): a robot of the same name
//                       already on the domain makes configure fail, naming it
//                       (src/robot_name.hpp)
// Real robots only:
//   sides               [sensors, actuators] (default): which sides this instance runs.
//                       sensors: publishes the description (latched) and a sensor sample
//                       per tick; the backend is never powered. actuators: commands and
//                       control parameters in, joint control, backend powered.
//                       Two instances (one per side, e.g. in two processes) work when
//                       the hardware accepts two connections.
//   urdf                the robot's URDF, named in the description (default: the
//                       backend's description.urdf)
//   floating_base       whether the description says floating base (default: the
//                       backend's description.floating_base)
// Simulations only:
//   lockstep              false (default): do not wait for commands; true: wait for them
//   real_time             pace at real time (default: true without lockstep, false with)
//   real_time_max_lag_s   a real-time tick late by up to this is caught up (default 0.02 s);
//                         a longer delay (the process stalled) is not: the simulation
//                         pauses with its process, counted in real_time_stalls
//   lockstep_controllers  names of the controllers (ActuatorCommand.controller) to wait for
//   lockstep_timeout_s    longest wait for a tick's commands (default 2 s; then a warning)
//   lockstep_start_timeout_s  longest wait for the first tick's commands, while the
//                         controllers start (default 60 s)
//   duration_s            stop stepping after this simulated time (default 0: never),
//                         printing "TYPE 'ROBOT': duration_s D reached: stopped stepping"
//   ground_truth_file     also write every tick's ground truth to this MCAP file (relative:
//                         to the process's working directory; default: none), stamped with
//                         simulated time only, complete once stepping ends: two lockstep
//                         runs that are the same give the same bytes (`wbi bag compare`)
// Status counters: those of the actuator side (rejected_commands,
// rejected_parameters, watchdog_trips, limit_clamps, …), lockstep_timeouts (in
// lockstep) and real_time_stalls (in real time); the last rejection or trip in
// words as the last error. A simulation that throws (diverged) stops stepping
// with "simulation stopped at t = T s: …" as the last error.
// Events (wbi/events): WATCHDOG_TRIP, COMMANDS_REJECTED, CLAIM_CHANGED and
// CLAIM_FORCED from the actuator side, LOOP_STALL from the tick pacers,
// DIVERGENCE when the simulation throws (docs/events.md).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <wbi/actuation/robot_backend.hpp>
#include <wbi/actuation/simulation_backend.hpp>
#include <wbi/runtime/registry.hpp>

namespace wbi::robot {

// Makes the backend from the component's parameters (reading its own keys).
using BackendFactory =
    std::function<std::unique_ptr<actuation::RobotBackend>(const runtime::Parameters&)>;
using SimulationFactory =
    std::function<std::unique_ptr<actuation::SimulationBackend>(const runtime::Parameters&)>;

// A component type for a real robot: the runner's period paces it.
void register_driver(runtime::Registry& registry, const std::string& type, BackendFactory factory,
                     std::string description = "robot driver: sensor samples out, commands in");

// A component type for a simulated robot: the simulation paces itself (lockstep
// or real time: tick pacers), plus ground truth and wbi/clock.
void register_simulation(runtime::Registry& registry, const std::string& type,
                         SimulationFactory factory, std::string description);

}  // namespace wbi::robot
