// One process of a deploy file as the runtime's host document: the deploy
// format is read here, not in the runtime (wbi/runtime/host.hpp).
#include "wbi/deploy/process_host.hpp"

#include <stdexcept>

#include "wbi/deploy/placement.hpp"

namespace wbi::deploy {

namespace {

std::string line_of(const std::string& file, const YAML::Node& node) {
  return file + ":" + std::to_string(node.Mark().line + 1);
}

}  // namespace

YAML::Node process_host_document(const YAML::Node& deploy, const std::string& file,
                                 const std::string& process) {
  const YAML::Node processes = deploy["processes"];
  if (processes && processes.IsSequence()) {
    for (const auto& entry : processes) {
      if (entry.IsMap() && entry["name"] && entry["name"].IsScalar() &&
          entry["name"].Scalar() == process) {
        if (!entry["components"]) {
          throw std::runtime_error(line_of(file, entry) + ": process '" + process +
                                   "' has no 'components' to host");
        }
        YAML::Node host;
        host["components"] = entry["components"];
        for (const char* key : {"domain_id", "qos_file", kNetworkKey, kSecurityKey}) {
          if (deploy[key]) {
            host[key] = deploy[key];
          }
        }
        return host;
      }
    }
  }
  throw std::runtime_error(file + ": no process named '" + process + "' in the deploy file");
}

YAML::Node load_process_host(const std::string& deploy_file, const std::string& process) {
  return process_host_document(load_deploy_file(deploy_file), deploy_file, process);
}

}  // namespace wbi::deploy
