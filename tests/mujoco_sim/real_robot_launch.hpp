// What the launch tests of the real robots' deploy files share: why one cannot
// run in this build (no MuJoCo, or no ../shared models beside the repository),
// and `wbi launch deploy/FILE`, with --duration only as a safety net.
#pragma once

#include <string>

#include "child_process.hpp"
#include "test_support.hpp"

namespace wbi::test {

// Empty when the test can run, else the line to skip with.
inline std::string real_robot_skip_reason() {
#ifndef WBI_WITH_MUJOCO
  return "this build has no MuJoCo (install libmujoco-dev: scripts/install-deps)";
#else
  return shared_models_dir() ? "" : kSharedMissing;
#endif
}

inline ChildProcess launch_deploy_file(const std::string& file, int duration_s) {
  return ChildProcess(binary_dir() / "bin" / "wbi",
                      {"launch", (source_dir() / "deploy" / file).string(), "--duration",
                       std::to_string(duration_s)});
}

}  // namespace wbi::test
