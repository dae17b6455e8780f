// Deploy files rewritten for a test: the project's own, with their relative
// paths made absolute (the copy is written under the build tree) and a few
// lines changed, e.g. a shorter exit_after_s.
#pragma once

#include <filesystem>
#include <string>

namespace wbi::test {

std::string read_text(const std::filesystem::path& file);

// Replaces every occurrence; returns how many there were.
int replace_all(std::string& text, const std::string& from, const std::string& to);

// deploy/<name>'s text with its model (../models/, ../../shared/) and robot
// configuration (config: robots/) paths made absolute.
std::string deploy_text(const std::string& name);

// Writes text to <build>/tests/<name> and returns that path.
std::filesystem::path write_test_file(const std::string& name, const std::string& text);

}  // namespace wbi::test
