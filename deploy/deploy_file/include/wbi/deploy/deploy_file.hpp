// A deploy file: which processes run, what each hosts, how they start, stop
// and restart, and how they join DDS. Read once, checked once: this is the
// only reader of the format (the launcher, wbi_host and the wbi tools'
// --deploy all use it); every mistake names the file, the line and the field.
//
//   domain_id: 7                      # optional; WBI_DOMAIN_ID and --domain win
//   qos_file: my_qos.xml              # optional, relative to the deploy file
//   environment: {KEY: value}         # for every process
//   plugins: [my_lab]                 # for every components: process
//   network: {...}                    # across hosts; security: {...}  (placement_blocks.hpp)
//   summary: {process: controller, match: "final max joint error"}   # or a list of them
//   processes:
//     - name: robot
//       command: [wbi_host, robot.yaml]    # argv; or components: (run by wbi_host)
//       environment: {KEY: value}
//       required: true                     # its failure fails the launch (default true)
//       respawn: {enabled: false, delay: 1.0, max_retries: 3}
//       wait_for: {topics: [wbi/arm/sensors], timeout: 10}   # start once these exist
//       shutdown_on_exit: false            # true: when it exits, the launch stops
//       hang_timeout: 3.0                  # components: only; s without a status heartbeat
//                                          # or without loop iterations (a deadlocked loop)
//       host: my_host                      # components: only; their program (default wbi_host)
//       plugins: [my_controllers]          # components: only; after the file's
//
// A process joins with apply_join_keys(deploy.join, its name, options)
// (placement_blocks.hpp); the WBI_* environment and flags go on top.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include <wbi/dds/participant.hpp>

#include "wbi/deploy/placement_blocks.hpp"

namespace wbi::deploy {

struct RespawnPolicy {
  bool enabled = false;
  double delay_s = 1.0;  // between an exit and the restart
  int max_retries = 3;   // restarts allowed in all
};

struct ProcessSpec {
  std::string name;
  int line = 0;                      // of its entry in the file, for errors about it
  std::vector<std::string> command;  // argv; argv[0] is looked up next to `wbi`, then on PATH
  bool hosts_components = false;     // command is wbi_host running this process's components
  std::map<std::string, std::string> environment;
  bool required = true;
  RespawnPolicy respawn;
  std::vector<std::string> wait_for_topics;  // start only once these topics exist on the domain
  double wait_timeout_s = 10.0;
  bool shutdown_on_exit = false;        // its exit (any code) stops the whole launch
  std::vector<std::string> components;  // instance names, when hosts_components
  // The components list as written: the runtime's host format, read by
  // wbi_host (process_host.hpp); its nodes keep their marks for its errors.
  YAML::Node component_nodes;
  // > 0: the process is hung when none of its components' status heartbeats
  // came for this long (after the first); handled as a failure (respawn, or
  // required). 0: not watched.
  double hang_timeout_s = 0.0;
  // The plugins its wbi_host loads after the built-in one (wbi/runtime/plugins.hpp):
  // the deploy file's `plugins:`, then the process's own, as written.
  std::vector<std::string> plugins;
};

// The launch repeats, as its last lines, the last line of `process` that
// contains `match` (e.g. the demo's "final max joint error: X rad"), for
// each summary in file order (several controllers, several results).
struct SummarySpec {
  std::string process;
  std::string match;
};

struct DeployFile {
  std::filesystem::path path;
  // domain_id (checked in [0, 231]), qos_file (made absolute; it exists),
  // the network and security blocks.
  JoinKeys join;
  std::map<std::string, std::string> environment;
  std::vector<ProcessSpec> processes;
  std::vector<SummarySpec> summaries;

  bool secured() const { return join.security_directory.has_value(); }
};

// Reads and checks a deploy file. Throws std::runtime_error "FILE[:LINE]: …"
// naming the field (e.g. processes[1].respawn.delay) and what is wrong.
DeployFile read_deploy_file(const std::filesystem::path& path);
// The same, from YAML already parsed (its marks give the lines); `path` names
// it and anchors its relative paths.
DeployFile read_deploy_file(const YAML::Node& root, const std::filesystem::path& path);

}  // namespace wbi::deploy
