// A bad plugin met by the programs a user runs: `wbi_host` and `wbi launch`
// each refuse it with one line naming the file and exit 1, and the launch
// starts nothing; `wbi plugins` lists a lab's types with their plugin.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

fs::path test_plugin(const std::string& name) {
  return fs::path(WBI_TEST_PLUGIN_DIR) / ("libwbi_test_" + name + ".so");
}

fs::path program(const std::string& name) { return wbi::test::binary_dir() / "bin" / name; }

// A folder of this test's own, emptied.
fs::path scratch(const std::string& name) {
  const fs::path folder = fs::temp_directory_path() / ("wbi_test_plugin_processes_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

fs::path write(const fs::path& file, const std::string& text) {
  std::ofstream(file) << text;
  return file;
}

// Runs the program to its end (bounded) and returns its exit code and output.
std::pair<int, std::string> run(const fs::path& path, const std::vector<std::string>& args) {
  wbi::test::ChildProcess child(path, args);
  const auto code = child.wait(30s);
  EXPECT_TRUE(code.has_value()) << path << " did not end within 30 s";
  return {code.value_or(-1), child.output()};
}

// Whether one line of `text` has `first` and, after it, `second`.
bool line_with(const std::string& text, const std::string& first, const std::string& second) {
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string line = text.substr(start, end - start);
    const auto at = line.find(first);
    if (at != std::string::npos && line.find(second, at + first.size()) != std::string::npos) {
      return true;
    }
    start = end + 1;
  }
  return false;
}

int lines(const std::string& text) {
  int count = 0;
  for (char c : text) {
    count += c == '\n';
  }
  return count;
}

class BadPlugin : public ::testing::TestWithParam<const char*> {};

TEST_P(BadPlugin, WbiHostRefusesWithOneLine) {
  const fs::path plugin = test_plugin(GetParam());
  const fs::path folder = scratch(std::string("host_") + GetParam());
  const fs::path host_file =
      write(folder / "host.yaml",
            "plugins: [" + plugin.string() + "]\ncomponents:\n  - {name: ticker, type: idle}\n");
  const auto [code, output] = run(program("wbi_host"), {host_file.string()});
  EXPECT_EQ(code, 78) << output;  // a configuration error: `wbi launch` does not respawn it
  EXPECT_EQ(lines(output), 1) << output;
  EXPECT_NE(output.find("wbi_host: configuration error: plugin " + plugin.string()),
            std::string::npos)
      << output;
}

TEST_P(BadPlugin, LaunchRefusesBeforeStartingAnything) {
  const fs::path plugin = test_plugin(GetParam());
  const fs::path folder = scratch(std::string("launch_") + GetParam());
  const fs::path deploy =
      write(folder / "deploy.yaml", "plugins: [" + plugin.string() +
                                        "]\nprocesses:\n  - name: ticker\n    components:\n"
                                        "      - {name: ticker, type: idle, rate_hz: 10}\n");
  const auto [code, output] = run(program("wbi"), {"launch", deploy.string(), "--duration", "5"});
  EXPECT_EQ(code, 1) << output;
  EXPECT_EQ(lines(output), 1) << output;
  EXPECT_NE(output.find(deploy.string() + ": process 'ticker': plugin " + plugin.string()),
            std::string::npos)
      << output;
  EXPECT_EQ(output.find(": started"), std::string::npos) << "a process was started:\n" << output;
}

INSTANTIATE_TEST_SUITE_P(Refusals, BadPlugin,
                         ::testing::Values("never_built", "no_entry", "other_version", "other_abi",
                                           "duplicate", "throwing", "unresolved"));

TEST(PluginVerb, ListsALabsTypesWithTheirPlugin) {
  const auto [code, output] = run(program("wbi"), {"plugins", test_plugin("good").string()});
  ASSERT_EQ(code, 0) << output;
  EXPECT_TRUE(line_with(output, "wbi_test_good", WBI_TEST_PLUGIN_DIR)) << output;
  EXPECT_TRUE(line_with(output, "test_zero", "wbi_test_good")) << output;
  EXPECT_TRUE(line_with(output, "test_quiet", "wbi_test_good")) << output;
  EXPECT_TRUE(line_with(output, "pd_gravity", "wbi_builtin")) << output;
}

TEST(PluginVerb, WbiHostHelpListsTypesWithTheirPlugin) {
  const auto [code, output] =
      run(program("wbi_host"), {"--help", "--plugin", test_plugin("good").string()});
  ASSERT_EQ(code, 0) << output;
  EXPECT_NE(output.find("controller types (name, plugin, what it is):"), std::string::npos)
      << output;
  EXPECT_TRUE(line_with(output, "test_zero", "wbi_test_good")) << output;
}

}  // namespace
