// A participant placed as a deploy file says (its `network` and `security`
// blocks, with the WBI_DDS_* overrides), for the multi-host benches that run
// next to a deploy's processes on one of its hosts.
#pragma once

#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include <wbi/dds/participant.hpp>
#include <wbi/deploy/placement.hpp>

namespace wbi::bench {

// identity: the DDS Security identity when the file enables security (a
// process name of the deploy, or "observer" to only subscribe).
inline dds::ParticipantOptions deploy_participant_options(const std::string& deploy_file,
                                                          const std::string& name,
                                                          const std::string& identity) {
  dds::ParticipantOptions options;
  options.name = name;
  deploy::read_placement(YAML::LoadFile(deploy_file), deploy_file, identity, options);
  return options;
}

}  // namespace wbi::bench
