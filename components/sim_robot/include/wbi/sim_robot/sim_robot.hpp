// Component type "sim_robot": a simulated robot as DDS sees it — the robot
// driver's one loop (wbi/robot/robot_driver.hpp) with a simulation backend made
// by the engine the deploy file names, on the simulation's own time and pace:
//   read → publish sensors, ground truth, wbi/clock (tick k) → [lockstep: wait
//   for every controller's command for tick k] → [real time: wait for the wall
//   clock] → joint control → write → step.
//
// Parameters (the driver's, robot_driver.hpp "Simulations only", and):
//   robot                 required; the robot's name (topics wbi/<robot>/…)
//   engine                wbi (default): the project's own plant (robot_side/sim);
//                         any engine of the EngineRegistry (engine_registry.hpp);
//                         an unknown name is an error listing the registered ones
//   config                required; the engine's configuration file (for wbi: the
//                         simulation's YAML, robot_side/sim/README.md), relative to
//                         the host file
//   lockstep, lockstep_controllers, lockstep_timeout_s, lockstep_start_timeout_s,
//   real_time, duration_s, watchdog_timeout_s, reference_speed, hold_at_start: robot_driver.hpp
//   push_link, push_force, push_start_s, push_duration_s, push_point
//                         one push more than the config's `pushes:` (an experiment's
//                         scenario, so that one robot file serves every experiment):
//                         force [N, world axes] on the link from push_start_s [s] for
//                         push_duration_s (default 0.1 s) at push_point (link frame,
//                         default its origin)
//
// Status (wbi/status): rejected_commands, rejected_parameters, watchdog_trips,
// limit_clamps, lockstep_timeouts; the last rejection or trip in words.
// The loop runs on its own thread while ACTIVE (the simulation paces itself).
#pragma once

#include <memory>

#include <wbi/runtime/registry.hpp>

#include "wbi/sim_robot/engine_registry.hpp"

namespace wbi::sim_robot {

// Registers "sim_robot" over `engines`, looked up when a robot is made (so an
// engine a later plugin registers is found). A plugin passes the catalog's
// registry without owning it (it outlives the components).
void register_components(runtime::Registry& registry,
                         std::shared_ptr<const EngineRegistry> engines);
// Over the built-in engines only (tests, and programs without plugins).
void register_components(runtime::Registry& registry);

}  // namespace wbi::sim_robot
