// The controller host as a component (controller_host.hpp), and each
// controller type as a one-controller host of its own name.
//
// type controller_host:
//   the interface options (interface_options.hpp), and
//   joints             required; the controlled joints, by name
//   controllers        map: name → {type: <controller type> (default: the name),
//                      joints: the host's joints it commands (default: all; a
//                      planner: none), inputs: {INPUT: PLANNER[/OUTPUT]} its
//                      reference inputs fed by a planner of this host in the
//                      same tick (else from their topics), <its declared
//                      parameters>}; `hold` (the host's own,
//                      hold_controller.hpp) is always hosted and holds the
//                      joints no active controller commands
//   active             the controller(s) active from the first tick, a name or
//                      a list on disjoint joints (default: hold)
//   overrun_limit      ticks in a row over the period before the fallback (default 0:
//                      never; for real-time deploys, e.g. 10)
//   blend_s            after a switch, the last command's part decays with this
//                      time constant (default 0.1 s; 0: none)
//   switch_at_s, switch_to  scheduled switches: at each time (robot time since
//                      the first tick, increasing) the controller to activate
//                      in place of the active ones on its joints, e.g. [2, 12]
//                      and [balance, hold] (hold: every joint held)
//   switch_from        optional, one per switch: the controller whose joints it
//                      takes ("" : those on its joints), e.g. [arms, ""] with
//                      switch_to [hold, arms]: the arms held, then back
//   exit_after_s       end the process at this robot time (default 0: never)
//   wait_for_state     false (default): cycles on the clock at rate_hz, each with
//                      the newest estimate; true: a cycle starts when a new
//                      estimate arrives (waiting at most state_timeout_s,
//                      default 0.005 s) and answers it at once. In lockstep,
//                      on the clock, a cycle for a state answered already is
//                      skipped: each state is answered once, by one cycle
//                      that reads it throughout, as with true
//   init_timeout_s     wait for the robot's components (default 30 s)
//   progress_period_s  a progress line every so often (default 1 s; 0: none)
// type pd_gravity (and every other controller type): the same host with one
// controller of that type, active, whose parameters sit beside the host's.
// Times are the robot's: the source stamps of the state (the simulation's
// time in lockstep). Each switch is printed ("switch: pd → hold at t = …;
// torque step …"). At shutdown the host prints "stale cycles: N" and the
// active controller's summary (pd_gravity: "final max joint error: X rad"),
// as they were when the run ended (exit_after_s, a finished controller):
// not the ticks answered while the process shuts down.
#pragma once

#include <memory>

#include "wbi/controllers/controller.hpp"
#include "wbi/runtime/registry.hpp"

namespace wbi::controllers {

// Registers "controller_host", making controllers of `types` (looked up when a
// host is configured: a type a later plugin brings is found). A plugin passes
// the catalog's registry without owning it (it outlives the components).
void register_components(runtime::Registry& registry,
                         std::shared_ptr<const ControllerRegistry> types);
// A component type for each controller type of `types` (the one-controller
// host above), attributed to the controller's provider; a name already a
// component type is left to the map form. Once every plugin is in.
void register_single_controller_hosts(runtime::Registry& registry,
                                      std::shared_ptr<const ControllerRegistry> types);

}  // namespace wbi::controllers
