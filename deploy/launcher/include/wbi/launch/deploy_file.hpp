// A deploy file: which processes run, what each hosts, how they start, stop
// and restart. YAML; every error names the file, the line and the field.
//
//   domain_id: 7                      # optional; WBI_DOMAIN_ID and --domain win
//   qos_file: my_qos.xml              # optional, relative to the deploy file
//   environment: {KEY: value}         # for every process
//   network: {...}                    # across hosts; security: {...}  (wbi/deploy/placement.hpp)
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
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>

namespace wbi::launch {

struct RespawnPolicy {
  bool enabled = false;
  double delay_s = 1.0;  // between an exit and the restart
  int max_retries = 3;   // restarts allowed in all
};

struct ProcessSpec {
  std::string name;
  std::vector<std::string> command;  // argv; argv[0] is looked up next to `wbi`, then on PATH
  bool hosts_components = false;     // command is wbi_host running this process's components
  std::map<std::string, std::string> environment;
  bool required = true;
  RespawnPolicy respawn;
  std::vector<std::string> wait_for_topics;  // start only once these topics exist on the domain
  double wait_timeout_s = 10.0;
  bool shutdown_on_exit = false;        // its exit (any code) stops the whole launch
  std::vector<std::string> components;  // instance names, when hosts_components
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
  std::optional<int> domain_id;
  std::filesystem::path qos_file;  // empty: the built-in profiles
  std::map<std::string, std::string> environment;
  std::vector<ProcessSpec> processes;
  std::vector<SummarySpec> summaries;
  // The launcher's own participant (it waits for topics): the deploy's
  // network and security blocks, with the identity "launcher".
  dds::Discovery discovery = dds::Discovery::localhost;
  dds::NetworkOptions network;
  dds::SecurityOptions security;
};

// Reads and checks a deploy file. Throws std::runtime_error "FILE:LINE: …"
// naming the field (e.g. processes[1].respawn.delay) and what is wrong.
DeployFile load_deploy_file(const std::filesystem::path& path);

// The deploy's processes as one, named kOneProcessName (`wbi launch
// --one-process`): every process's components in one wbi_host, in file
// order, for when speed matters more than isolation. Waits for topics and
// respawn policies go (a component starts after the ones before it in the
// same process); the process stops the launch when it ends; the hang timeout
// is the longest; summaries are read from it. Throws naming a process that
// runs a command, processes with different host programs or environments
// that disagree, or a secured deployment (one identity per process).
inline constexpr const char* kOneProcessName = "all";
DeployFile in_one_process(DeployFile deploy);

// Only the processes named (`wbi launch FILE --process A,B`), in file order,
// with their summaries: the part of a deployment that runs on one host, the
// others started on theirs (each waits for the topics it names as usual).
// Throws std::runtime_error "FILE: --process: …" naming an unknown process
// (and listing the file's) or one named twice.
DeployFile only_processes(DeployFile deploy, const std::vector<std::string>& names);

// Loads every process's plugins as its wbi_host will (the built-in one first),
// so that a launch refuses a bad plugin before it starts anything. Throws
// std::runtime_error "FILE: process 'NAME': plugin …: why" (one line).
void check_plugins(const DeployFile& deploy);

}  // namespace wbi::launch
