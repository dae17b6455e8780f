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
  YAML::Node root;
  try {
    root = YAML::LoadFile(deploy_file);
  } catch (const YAML::BadFile&) {
    throw std::runtime_error(deploy_file + ": cannot read the deploy file");
  } catch (const YAML::Exception& error) {
    throw std::runtime_error(deploy_file + ":" + std::to_string(error.mark.line + 1) + ": " +
                             error.msg);
  }
  if (!root.IsMap()) {
    throw std::runtime_error(deploy_file + ": a deploy file is a map with a 'processes' list");
  }
  return process_host_document(root, deploy_file, process);
}

}  // namespace wbi::deploy
