// `wbi robot check FILE`: load and validate a robot config file
// (robot_side/robot_config/README.md) and summarise what it describes. An error
// is the parser's one line "file:line: key: what", exit 1.
#include <iostream>
#include <string>

#include <wbi/robot_config/robot_config.hpp>

#include "../options.hpp"
#include "../subcommands.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

constexpr const char* kCheckExample = "wbi robot check deploy/robots/arm.yaml";

int run_check(Args args) {
  Options opts("wbi robot check FILE",
               "Load a robot config file, check it against its URDF (every key, type, size, "
               "value and joint, link or frame name) and summarise it.");
  opts.positional("FILE", "the robot config file (YAML)");
  opts.example(kCheckExample, "the project's arm")
      .example("wbi robot check deploy/robots/humanoid.yaml",
               "the humanoid: contacts, IMU, F/T sensors");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  const std::string file = opts.get("FILE");
  const robot_config::RobotConfig c = robot_config::load_robot_config(file);
  std::cout << file << ": valid\n"
            << "  urdf: " << c.urdf << (c.fixed_base ? " (fixed base)" : "") << "\n"
            << "  joints: " << c.joints.size() << "\n";
  for (const auto& [name, joint] : c.joints) {
    std::cout << "    " << name << ": armature " << joint.armature << " kg m2, damping "
              << joint.damping << " N m s/rad, friction " << joint.friction << " N m\n";
  }
  std::cout << "  ground: z = " << c.ground.height << " m, friction " << c.ground.friction
            << "\n  contacts: " << c.contacts.size() << "\n";
  for (const auto& g : c.contacts) {
    std::cout << "    " << g.link << ": " << to_string(g.shape) << ", friction " << g.friction
              << "\n";
  }
  std::cout << "  imus: " << c.imus.size() << "\n";
  for (const auto& imu : c.imus) {
    std::cout << "    " << imu.name << " at " << imu.frame << "\n";
  }
  std::cout << "  force_torque: " << c.force_torque.size() << "\n";
  for (const auto& ft : c.force_torque) {
    std::cout << "    " << ft.name << " at " << ft.joint << "\n";
  }
  return kExitOk;
}

}  // namespace

int run_robot(Args args) {
  return run_subcommand("robot", args,
                        {{"check", "validate a robot config file against its URDF and summarise it",
                          kCheckExample, run_check}},
                        "Robot config files: robot_side/robot_config/README.md.\n");
}

}  // namespace wbi::cli
