// The DDS implementation of the whole-body interface: a thin proxy that
// reads sensors and state from the robot's topics, publishes actuator
// commands, and evaluates the model locally from the URDF (no round trip) or
// asks the robot's model service. Which one is configuration only.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string_view>

#include "wbi/dds_interface_options.hpp"
#include "wbi/whole_body_interface.hpp"

namespace wbi {

// "claim", "force", "none" (a deploy file's or a script's spelling); nullopt otherwise.
std::optional<DdsInterfaceOptions::Claim> claim_from_text(std::string_view text);

// Throws Error naming what is wrong in the options (e.g. no robot name, no URDF
// for a local model, a URDF that does not load).
std::unique_ptr<WholeBodyInterface> make_dds_interface(const DdsInterfaceOptions& options);

// Calls `on_state` on the DDS thread that delivers each new state estimate to
// `interface` (one from make_dds_interface), once a ReadMode::latest read
// returns it: an event-driven controller can run its cycle there, with no
// hand-off to a thread of its own. Keep it bounded: the thread delivers the
// participant's other samples too, so a call must never wait for one of
// them (a remote model's reply, a reference point). nullptr: no more calls;
// a call in progress is waited for. Throws Error for another interface.
void set_state_callback(WholeBodyInterface& interface, std::function<void()> on_state);

// Whether the robot of `interface` (one from make_dds_interface, after init())
// steps in lockstep: each tick only once its controllers answered the last.
// Throws Error for another interface or before init().
bool robot_in_lockstep(const WholeBodyInterface& interface);

}  // namespace wbi
