// MJCF text loaded by MuJoCo from memory, through its virtual file system:
// nothing touches the disk. Shared by the MuJoCo backend and `wbi render`.
#pragma once

#include <string>
#include <vector>

#include <mujoco/mujoco.h>

namespace wbi::mujoco_sim {

// A file the MJCF names (e.g. a mesh asset), given under `name`.
struct MemoryFile {
  std::string name;
  std::string data;
};

// The model of `xml` with `files` beside it. The caller owns it
// (mj_deleteModel). Throws std::runtime_error starting with `where` when
// MuJoCo rejects it.
mjModel* load_mjcf_from_memory(const std::string& xml, const std::vector<MemoryFile>& files,
                               const std::string& where);

}  // namespace wbi::mujoco_sim
