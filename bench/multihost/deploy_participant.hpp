// A participant that joins a deployment as the wbi tools do (dds/README.md,
// "Joining a deployment": the deploy file, then the WBI_* environment), for the
// multi-host benches that run next to a deploy's processes on one of its hosts.
#pragma once

#include <memory>
#include <string>

#include <wbi/dds/join_options.hpp>
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
  deploy::read_join_options(deploy_file, identity, options);
  // The bench's own identity, whatever the file's processes use.
  options.security.identity = identity;
  dds::apply_environment(options);
  return options;
}

}  // namespace wbi::bench
