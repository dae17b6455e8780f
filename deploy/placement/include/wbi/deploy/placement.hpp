// Joining the deployment a deploy file describes, for the participants that
// are none of its processes (`wbi ... --deploy FILE`, wbi.DdsInterface, the
// multi-host benches). The file is read by the one deploy-file reader
// (deploy_file.hpp); its placement blocks: placement_blocks.hpp.
#pragma once

#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/deploy/deploy_file.hpp>
#include <wbi/deploy/placement_blocks.hpp>

namespace wbi::deploy {

// The file's domain_id, qos_file (relative to it), network and security
// blocks on top of `options`, as the participant `identity`. Throws
// std::runtime_error "FILE:LINE: ..." for any mistake in the file.
void read_join_options(const std::string& file, const std::string& identity,
                       dds::ParticipantOptions& options);

}  // namespace wbi::deploy
