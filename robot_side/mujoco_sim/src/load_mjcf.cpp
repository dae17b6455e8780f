#include "wbi/mujoco_sim/load_mjcf.hpp"

#include <cstring>
#include <memory>
#include <stdexcept>

namespace wbi::mujoco_sim {

namespace {

// Copies `data` into the virtual file system as `name`.
void add_file(mjVFS* vfs, const std::string& name, const std::string& data,
              const std::string& where) {
  if (mj_makeEmptyFileVFS(vfs, name.c_str(), static_cast<int>(data.size())) != 0) {
    throw std::runtime_error(where + ": MuJoCo: cannot make the in-memory file " + name);
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs, name.c_str())], data.data(), data.size());
}

}  // namespace

mjModel* load_mjcf_from_memory(const std::string& xml, const std::vector<MemoryFile>& files,
                               const std::string& where) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const std::string name = "robot.xml";
  try {
    add_file(vfs.get(), name, xml, where);
    for (const auto& file : files) {
      add_file(vfs.get(), file.name, file.data, where);
    }
  } catch (...) {
    mj_deleteVFS(vfs.get());
    throw;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(name.c_str(), vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (m == nullptr) {
    throw std::invalid_argument(where + ": MuJoCo rejected the model: " + error);
  }
  return m;
}

}  // namespace wbi::mujoco_sim
