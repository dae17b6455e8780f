// `wbi launch FILE --process A,B`: the part of a deployment one host runs.
#include <algorithm>
#include <stdexcept>

#include "wbi/launch/deploy_file.hpp"

namespace wbi::launch {

DeployFile only_processes(DeployFile deploy, const std::vector<std::string>& names) {
  const auto refuse = [&](const std::string& why) {
    throw std::runtime_error(deploy.path.string() + ": --process: " + why);
  };
  if (names.empty()) {
    refuse("no process named");
  }
  std::string known;
  for (const ProcessSpec& process : deploy.processes) {
    known += (known.empty() ? "" : ", ") + process.name;
  }
  for (auto name = names.begin(); name != names.end(); ++name) {
    const auto named = [&](const ProcessSpec& process) { return process.name == *name; };
    if (std::none_of(deploy.processes.begin(), deploy.processes.end(), named)) {
      refuse("no process named '" + *name + "' (the file has: " + known + ")");
    }
    if (std::find(names.begin(), name, *name) != name) {
      refuse("process '" + *name + "' named twice");
    }
  }
  const auto kept = [&](const std::string& process) {
    return std::find(names.begin(), names.end(), process) != names.end();
  };
  // File order is kept: a process's topic waits name what the others publish,
  // here or on another host.
  std::erase_if(deploy.processes, [&](const ProcessSpec& process) { return !kept(process.name); });
  std::erase_if(deploy.summaries,
                [&](const SummarySpec& summary) { return !kept(summary.process); });
  return deploy;
}

}  // namespace wbi::launch
