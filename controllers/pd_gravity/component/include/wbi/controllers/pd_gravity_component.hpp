// PD + gravity as a component (type "pd_gravity"): the controller of
// pd_gravity.hpp, connected through the DDS whole-body interface, run by the
// component runtime at its rate (default 1 kHz in the deploy files).
//
// Parameters:
//   robot            required; the robot's name
//   model            local (default): evaluate the model in this process from urdf;
//                    remote: ask the robot's model service (wbi/<robot>/model)
//   urdf             the robot's URDF, relative to the host file; required for a local
//                    model, optional for a remote one (frame names only)
//   model_timeout_s  deadline of one remote model call (default 0.2 s)
//   model_backend    the dynamics library of a local model: wbi (default) or dart (when
//                    built with DART; model_service/README.md); a remote model's is the
//                    model service's `backend` parameter
//   joints           required; the controlled joints, by name
//   target           q_d, one per controlled joint [rad]
//   bandwidth_hz     gains from the mass matrix's joint block at q_d (the whole block):
//                    kp = ω² M_jj, kd = 2ω M_jj
//                    (critically damped), ω = 2π bandwidth (default 5 Hz); or
//   kp, kd           explicit gains, one per joint (both or neither)
//   controller       name on the commands (default: the instance name)
//   claim            claim (default): init claims the joints from the robot and fails
//                    naming any other owner; force: takes them (a supervisor); none:
//                    no claim (a robot that answers none, e.g. a test peer)
//   max_age_s        oldest state accepted (default 0.05 s)
//   wait_for_state   false (default): cycles on the clock at rate_hz, each using the
//                    newest estimate; true: event-driven, a cycle starts when an
//                    estimate newer than the last one arrives (waiting at most
//                    state_timeout_s, default 0.005 s) and answers it at once, so the
//                    command follows its sensor sample by one pipeline pass; a cycle
//                    then overruns when it takes longer than 1/rate_hz
//   init_timeout_s   wait for the robot's components (default 30 s)
//   progress_period_s  a progress line every so often (default 1 s; 0: none)
// At shutdown it prints "final max joint error: X rad".
#pragma once

#include "wbi/runtime/registry.hpp"

namespace wbi::controllers {

void register_components(runtime::Registry& registry);

}  // namespace wbi::controllers
