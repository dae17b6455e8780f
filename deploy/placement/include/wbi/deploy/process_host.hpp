// One process of a deploy file (deploy/README.md) as the host document the
// runtime's Host reads (wbi/runtime/host.hpp): the process's `components`
// list and its plugins. The deploy's join keys (domain_id, qos_file, network,
// security) stay with the deploy file, read and checked once by its reader
// (deploy_file.hpp): wbi_host applies them with apply_join_keys through the
// Host's placement reader. The component nodes keep their marks, so errors
// about them still name the deploy file's lines. Used by `wbi_host DEPLOY
// --process NAME`; the runtime itself does not know the deploy format.
// Several processes hosted as one (`--process A,B,C`, `wbi launch --one-process`)
// give their components in the order named.
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include <wbi/deploy/deploy_file.hpp>

namespace wbi::deploy {

// Throws std::runtime_error "FILE[:LINE]: what" for an unknown process or one
// without components.
YAML::Node process_host_document(const DeployFile& deploy,
                                 const std::vector<std::string>& processes);

struct ProcessHost {
  JoinKeys join;        // the deploy's (apply_join_keys)
  YAML::Node document;  // the host document
};

// Reads and checks `deploy_file`, then as above; `processes` is one name or
// several joined by ',' ("robot,estimator,controller").
ProcessHost load_process_host(const std::string& deploy_file, const std::string& processes);

}  // namespace wbi::deploy
