// One entry of a deploy file's `processes` list (deploy_file.hpp).
#pragma once

#include <string>
#include <vector>

#include "wbi/deploy/deploy_file.hpp"
#include "yaml_fields.hpp"

namespace wbi::deploy::detail {

// `field` is its path ("processes[1]"); `plugins` the file's, which a
// components: process loads before its own.
ProcessSpec read_process(const YamlFields& in, const YAML::Node& node, const std::string& field,
                         const std::vector<std::string>& plugins);

}  // namespace wbi::deploy::detail
