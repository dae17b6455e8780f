// Which robots have a controller host on the domain, found through DDS
// discovery: for `wbi controller` and `wbi param` without --robot, and for
// scripts. A host is the writer of wbi/<robot>/controllers/reply.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>

namespace wbi::controllers {

// The robots whose controller host discovery knows now, sorted, each once.
// Hosts whose process (on this machine) has ended are left out: discovery
// keeps them until their lease ends.
std::vector<std::string> controller_hosts(const dds::Participant& participant);

// Waits at most `timeout` for a first host, then until no endpoint came or
// went for `settle`, or for as long as the first host took to appear if that
// was longer (a loaded machine discovers slowly): discovery has no "done"
// event, but the endpoints of the processes already on the domain arrive in
// one burst after joining, so a quiet spell means the others are known too.
// Returns controller_hosts() then (empty: none within `timeout`).
std::vector<std::string> find_controller_hosts(
    const dds::Participant& participant, std::chrono::nanoseconds timeout,
    std::chrono::nanoseconds settle = std::chrono::milliseconds(300));

}  // namespace wbi::controllers
