// How a component ends the process that hosts it: at the end of its run
// (exit code 0) or on a fault it cannot recover from (non-zero), e.g. a
// simulation that diverged. The component asks; the host decides how: wbi_host
// installs a handler that shuts its components down as SIGTERM would and then
// exits with the code, so that `wbi launch` sees the process end. Without a
// handler (components run in a test or a program of one's own) the request is
// only recorded: a library never signals the process it is linked into.
#pragma once

#include <functional>
#include <optional>

namespace wbi::runtime {

// Exit codes a supervisor reads (`wbi launch`, deploy/README.md "Exit codes").
// A process ending with either is not respawned: starting it again cannot
// change the outcome. The values are sysexits.h's, which shells and process
// managers already know.
inline constexpr int kExitConfigurationError = 78;  // EX_CONFIG: bad parameter, unknown type,
                                                    // missing file, bad command line
inline constexpr int kExitRunFailed = 65;  // EX_DATAERR: the run ended, but its figures are
                                           // computed over nothing (no reference point came)
// EX_TEMPFAIL: its start stalled on something a new start cures (a DDS Security
// handshake, handshake_watch.hpp): `wbi launch` starts it again at once,
// whatever its respawn policy, a few times.
inline constexpr int kExitStartStalled = 75;

// Installed once by the host program, before its components start.
void set_process_exit_handler(std::function<void(int exit_code)> handler);

// The first request wins; later ones are ignored. Thread-safe.
void request_process_exit(int exit_code);

// The code of the first request (a negative one counts as 1); none before it.
std::optional<int> requested_process_exit_code();

}  // namespace wbi::runtime
