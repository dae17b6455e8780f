#include "deploy_text.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "test_support.hpp"

namespace wbi::test {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) {
    throw std::runtime_error(file.string() + ": cannot read");
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

int replace_all(std::string& text, const std::string& from, const std::string& to) {
  int count = 0;
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
    ++count;
  }
  return count;
}

std::string deploy_text(const std::string& name) {
  const std::filesystem::path deploy = source_dir() / "deploy";
  std::string text = read_text(deploy / name);
  replace_all(text, "../../shared/", (source_dir().parent_path() / "shared").string() + "/");
  replace_all(text, "../models/", (source_dir() / "models").string() + "/");
  replace_all(text, "config: robots/", "config: " + (deploy / "robots").string() + "/");
  return text;
}

std::filesystem::path write_test_file(const std::string& name, const std::string& text) {
  const std::filesystem::path out = binary_dir() / "tests" / name;
  std::ofstream(out) << text;
  return out;
}

}  // namespace wbi::test
