// A real robot on DDS: register a component type that drives your RobotBackend
// (wbi/actuation/robot_backend.hpp) with the same sensor and actuator sides as
// sim_robot, one read → control → write cycle per tick of the runner:
//
//   wbi::robot::register_driver(registry, "my_robot", [](const runtime::Parameters& p) {
//     return std::make_unique<MyBackend>(p.require<std::string>("device"));
//   });
//
// and deploy it with rate_hz = the backend rate:
//
//   - name: robot
//     type: my_robot
//     rate_hz: 1000
//     parameters: {robot: my_robot, device: /dev/…}
//
// Parameters (besides the backend's own, which the factory reads):
//   robot               required; topics wbi/<robot>/…
//   sides               [sensors, actuators] (default): which sides this instance runs.
//                       sensors: publishes the description (latched) and a sensor sample
//                       per tick; the backend is never powered. actuators: commands and
//                       control parameters in, joint control, backend powered.
//                       Two instances (one per side, e.g. in two processes) work when
//                       the hardware accepts two connections.
//   watchdog_timeout_s  joint controller watchdog (default 0.1 s; 0 disables)
//   reference_speed     default POSITION-mode speed [rad/s] (default 0.5)
//   hold_at_start       true (default): joints hold their position until commanded
//   urdf                the robot's URDF, named in the description (default: none)
//   floating_base       false (default): whether the description says floating base
// Status counters: those of the actuator side (rejected_commands, watchdog_trips, …).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <wbi/actuation/robot_backend.hpp>
#include <wbi/runtime/registry.hpp>

namespace wbi::robot {

using BackendFactory =
    std::function<std::unique_ptr<actuation::RobotBackend>(const runtime::Parameters&)>;

void register_driver(runtime::Registry& registry, const std::string& type, BackendFactory factory,
                     std::string description = "robot driver: sensor samples out, commands in");

}  // namespace wbi::robot
