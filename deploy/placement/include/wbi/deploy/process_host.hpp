// One process of a deploy file (deploy/README.md) as the host document the
// runtime's Host reads (wbi/runtime/host.hpp): the entry of `processes` named
// `process`, its `components` list, and the deploy's domain_id, qos_file,
// network and security. The nodes keep their marks, so errors about the
// components still name the deploy file's lines. Used by `wbi_host DEPLOY
// --process NAME`; the runtime itself does not know the deploy format.
// Several processes hosted as one (`--process A,B,C`, `wbi launch --one-process`)
// give their components in the order named.
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace wbi::deploy {

// From a deploy file already parsed; `file` names it in errors. Throws
// std::runtime_error "FILE[:LINE]: what" for an unknown process or one
// without components.
YAML::Node process_host_document(const YAML::Node& deploy, const std::string& file,
                                 const std::string& process);
YAML::Node process_host_document(const YAML::Node& deploy, const std::string& file,
                                 const std::vector<std::string>& processes);

// Reads `deploy_file`, then as above; `processes` is one name or several
// joined by ',' ("robot,estimator,controller").
YAML::Node load_process_host(const std::string& deploy_file, const std::string& processes);

}  // namespace wbi::deploy
