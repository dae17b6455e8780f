// `wbi robot check FILE`: load and validate a robot config file
// (robot_side/robot_config/README.md) and summarise what it describes. An error
// is the parser's one line "file:line: key: what", exit 1.
#include <iostream>
#include <string>

#include <wbi/robot_config/robot_config.hpp>

#include "../options.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

int run_check(Args args) {
  Options opts("wbi robot check FILE",
               "Load a robot config file, check it against its URDF (every key, type, size, "
               "value and joint, link or frame name) and summarise it.");
  opts.positional("FILE", "the robot config file (YAML)");
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
  if (args.empty()) {
    throw UsageError("missing sub-verb: check");
  }
  const std::string& sub = args[0];
  if (sub == "--help" || sub == "-h") {
    std::cout << "usage: wbi robot check FILE\n\n"
                 "Robot config files (robot_side/robot_config/README.md).\n\n"
                 "sub-verbs:\n"
                 "  check  validate a robot config file against its URDF and summarise it\n";
    return kExitOk;
  }
  if (sub == "check") {
    return run_check(args.subspan(1));
  }
  throw UsageError("unknown sub-verb '" + sub + "' (check)");
}

}  // namespace wbi::cli
