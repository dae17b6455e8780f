// Runs the processes of a deploy file: starts them in order (each once the
// topics it waits for exist), prefixes their output with their name, restarts
// them by their respawn policy, and stops them all — SIGTERM, then SIGKILL
// after a grace period — on Ctrl-C/SIGTERM, after a duration, when a process
// marked shutdown_on_exit ends, or when a required process fails.
#pragma once

#include <ostream>

#include "wbi/launch/deploy_file.hpp"

#include <wbi/dds/join_options.hpp>

namespace wbi::launch {

struct LaunchOptions {
  double duration_s = 0.0;    // stop after this long; 0: until something else stops the launch
  double stop_grace_s = 5.0;  // SIGTERM → SIGKILL delay
  // Command-line join options (`wbi launch --domain ...`): above the deploy
  // file and the environment, for the launcher and every process it starts.
  dds::JoinOverrides join;
};

// Returns the exit code: 0 when every process's last run did its part; 1 when
// one could not start, failed (even an optional one), never said its
// components run, or had to be killed; 130 when interrupted. Installs SIGINT/SIGTERM handlers while
// running.
int run_launch(const DeployFile& deploy, const LaunchOptions& options, std::ostream& out);

// The launcher's pid, in the environment of every process it starts.
inline constexpr const char* kLauncherPidVariable = "WBI_LAUNCHER_PID";

// For a process `wbi launch` started directly (its parent is kLauncherPidVariable's
// pid): asks the kernel for SIGTERM when the launcher dies, even by SIGKILL, so
// that no component — a controller commanding a robot — outlives its
// supervisor. Returns whether it did (false: not started by a launcher, or by
// way of another process such as a shell). Linux only; call before threads start.
bool stop_when_launcher_dies();

}  // namespace wbi::launch
