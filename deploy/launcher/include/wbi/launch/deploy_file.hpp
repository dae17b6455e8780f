// What the launcher does with a deploy file, read and checked by the one
// deploy-file reader (wbi/deploy/deploy_file.hpp, its format): the part of it
// that runs here (--process), all of it in one process (--one-process), and
// its plugins checked before anything starts.
#pragma once

#include <string>
#include <vector>

#include <wbi/deploy/deploy_file.hpp>

namespace wbi::launch {

using deploy::DeployFile;
using deploy::ProcessSpec;
using deploy::RespawnPolicy;
using deploy::SummarySpec;

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
