// `wbi launch FILE --one-process`: a deploy's processes hosted by one wbi_host.
#include <algorithm>
#include <stdexcept>

#include "wbi/launch/deploy_file.hpp"

namespace wbi::launch {

namespace {

[[noreturn]] void refuse(const DeployFile& deploy, const std::string& why) {
  throw std::runtime_error(deploy.path.string() + ": --one-process: " + why);
}

}  // namespace

DeployFile in_one_process(DeployFile deploy) {
  if (deploy.secured()) {
    refuse(deploy,
           "a secured deployment gives each process its own identity; run its processes "
           "apart");
  }
  ProcessSpec one;
  one.name = kOneProcessName;
  one.hosts_components = true;
  one.shutdown_on_exit = true;  // the only process: its end is the launch's
  std::string names;
  for (const ProcessSpec& process : deploy.processes) {
    if (!process.hosts_components) {
      refuse(deploy, "process '" + process.name +
                         "' runs a command, not components: only components can share a process");
    }
    // command = {host, deploy file, "--process", name}: one host program for all.
    if (one.command.empty()) {
      one.command = process.command;
    } else if (process.command.front() != one.command.front()) {
      refuse(deploy, "processes '" + deploy.processes.front().name + "' and '" + process.name +
                         "' name different host programs (" + one.command.front() + ", " +
                         process.command.front() + ")");
    }
    for (const auto& [key, value] : process.environment) {
      const auto [at, added] = one.environment.emplace(key, value);
      if (!added && at->second != value) {
        refuse(deploy, "process '" + process.name + "' sets " + key + "=" + value +
                           ", an earlier one " + key + "=" + at->second);
      }
    }
    names += (names.empty() ? "" : ",") + process.name;
    one.plugins.insert(one.plugins.end(), process.plugins.begin(), process.plugins.end());
    one.components.insert(one.components.end(), process.components.begin(),
                          process.components.end());
    one.hang_timeout_s = std::max(one.hang_timeout_s, process.hang_timeout_s);
  }
  if (deploy.processes.empty()) {
    refuse(deploy, "no process to host");
  }
  one.command.back() = names;
  deploy.processes = {one};
  for (SummarySpec& summary : deploy.summaries) {
    summary.process = kOneProcessName;
  }
  return deploy;
}

}  // namespace wbi::launch
