// The protocol's fetchAsset: the files Foxglove's URDF layer asks for (the
// URDF's meshes, as package://, file:// or relative URIs), served only from
// the folders given (--mesh-path, and each robot's URDF folder), so that a
// client cannot read any other file of the host.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wbi::bridge {

class AssetFolders {
 public:
  void add(const std::filesystem::path& folder);  // ignored when it does not exist

  // The file's bytes; throws std::runtime_error naming the URI and why.
  // package://PKG/REST is looked up as FOLDER/PKG/REST, then FOLDER/REST.
  std::vector<std::uint8_t> read(const std::string& uri) const;

 private:
  std::vector<std::filesystem::path> candidates(const std::string& uri) const;
  bool inside_a_folder(const std::filesystem::path& file) const;

  std::vector<std::filesystem::path> folders_;  // canonical
};

}  // namespace wbi::bridge
