#include "assets.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace wbi::bridge {

namespace fs = std::filesystem;

namespace {

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.compare(0, prefix.size(), prefix) == 0;
}

}  // namespace

void AssetFolders::add(const fs::path& folder) {
  std::error_code ec;
  const auto canonical = fs::canonical(folder, ec);
  if (!ec && fs::is_directory(canonical) &&
      std::find(folders_.begin(), folders_.end(), canonical) == folders_.end()) {
    folders_.push_back(canonical);
  }
}

std::vector<fs::path> AssetFolders::candidates(const std::string& uri) const {
  std::vector<fs::path> out;
  if (starts_with(uri, "file://")) {
    out.emplace_back(uri.substr(7));
    return out;
  }
  std::string relative = uri;
  std::string package;
  if (starts_with(uri, "package://")) {
    relative = uri.substr(10);
    const auto slash = relative.find('/');
    package = relative.substr(0, slash);
    relative = slash == std::string::npos ? std::string() : relative.substr(slash + 1);
  } else if (uri.find("://") != std::string::npos) {
    throw std::runtime_error(uri + ": only package://, file:// and relative URIs are served");
  }
  for (const auto& folder : folders_) {
    if (!package.empty()) {
      out.push_back(folder / package / relative);
    }
    out.push_back(folder / relative);
  }
  return out;
}

bool AssetFolders::inside_a_folder(const fs::path& file) const {
  return std::any_of(folders_.begin(), folders_.end(), [&](const fs::path& folder) {
    const auto [end, _] = std::mismatch(folder.begin(), folder.end(), file.begin(), file.end());
    return end == folder.end();
  });
}

std::vector<std::uint8_t> AssetFolders::read(const std::string& uri) const {
  for (const auto& candidate : candidates(uri)) {
    std::error_code ec;
    const auto file = fs::canonical(candidate, ec);
    if (ec || !fs::is_regular_file(file)) {
      continue;
    }
    if (!inside_a_folder(file)) {
      throw std::runtime_error(uri +
                               ": outside the served folders (--mesh-path, the URDF's folder)");
    }
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }
  throw std::runtime_error(uri +
                           ": not found in the served folders (--mesh-path, the URDF's folder)");
}

}  // namespace wbi::bridge
