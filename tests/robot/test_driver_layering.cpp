// A real robot's driver links no simulator (ARCHITECTURE.md, layering), read
// from the build rather than from names in the sources:
//   - the link closure of wbi_robot, written by CMake from the targets' link
//     properties (tests/robot/CMakeLists.txt), holds neither wbi_sim nor MuJoCo,
//     while that of wbi_sim_robot, the control, holds wbi_sim;
//   - the headers that the compiler recorded for each object of wbi_robot
//     (ninja's deps log, or the .o.d files of the Makefile generators) include
//     none of robot_side/sim, components/sim_robot or MuJoCo.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines_of(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) {
      lines.push_back(line);
    }
  }
  return lines;
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool mentions_mujoco(const std::string& text) {
  return lower(text).find("mujoco") != std::string::npos;
}

bool contains(const std::vector<std::string>& items, const std::string& item) {
  return std::find(items.begin(), items.end(), item) != items.end();
}

// Whether `path` lies in the folder `dir`.
bool under(const fs::path& path, const fs::path& dir) {
  const auto relative = path.lexically_relative(dir);
  return !relative.empty() && *relative.begin() != "..";
}

std::string run(const std::string& command) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    return out;
  }
  std::array<char, 4096> buffer{};
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) {
    out.append(buffer.data(), n);
  }
  pclose(pipe);
  return out;
}

// The headers the compiler recorded for each object, paths as recorded.
std::map<std::string, std::vector<std::string>> recorded_dependencies(
    const std::vector<std::string>& objects) {
  std::map<std::string, std::vector<std::string>> deps;
  const fs::path build = wbi::test::binary_dir();
  if (std::string(WBI_GENERATOR).find("Ninja") != std::string::npos) {
    // `ninja -t deps OBJ…` prints "OBJ: #deps N, …" then one indented path a line.
    std::string command =
        std::string("'") + WBI_MAKE_PROGRAM + "' -C '" + build.string() + "' -t deps";
    for (const auto& object : objects) {
      command +=
          " '" + fs::path(object).lexically_normal().lexically_relative(build).string() + "'";
    }
    std::istringstream out(run(command));
    std::string current;
    for (std::string line; std::getline(out, line);) {
      if (line.empty()) {
        continue;
      }
      if (line[0] != ' ') {
        current = line.substr(0, line.find(':'));
        deps[current];
      } else {
        deps[current].push_back(line.substr(line.find_first_not_of(' ')));
      }
    }
    return deps;
  }
  // Makefile generators keep the compiler's depfile beside the object: "OBJ: a.hpp \".
  for (const auto& object : objects) {
    std::ifstream in(object + ".d");
    auto& list = deps[fs::path(object).lexically_normal().lexically_relative(build).string()];
    for (std::string token; in >> token;) {
      if (token != "\\" && token.back() != ':') {
        list.push_back(token);
      }
    }
  }
  return deps;
}

TEST(DriverLayering, TheDriverLibraryLinksNoSimulator) {
  const fs::path dir = WBI_LAYERING_DIR;
  const auto robot = lines_of(dir / "wbi_robot.link");
  const auto sim_robot = lines_of(dir / "wbi_sim_robot.link");
  ASSERT_FALSE(robot.empty()) << "no link closure in " << dir;
  // The closure sees what wbi_robot links, and a static library's private links.
  EXPECT_TRUE(contains(robot, "wbi_actuation"));
  EXPECT_TRUE(contains(robot, "wbi_runtime"));
  EXPECT_TRUE(contains(sim_robot, "wbi_sim")) << "the control: sim_robot links the own plant";
  EXPECT_TRUE(contains(sim_robot, "wbi_robot"));
  for (const auto& library : robot) {
    EXPECT_NE(library, "wbi_sim") << "wbi_robot links the simulator";
    EXPECT_NE(library, "wbi_sim_robot") << "wbi_robot links the simulation component";
    EXPECT_FALSE(mentions_mujoco(library)) << "wbi_robot links " << library;
  }
}

// The headers of the named target's objects that lie in a simulator: under
// robot_side/sim or components/sim_robot, or MuJoCo's.
std::vector<std::string> simulator_headers(const std::string& target) {
  const auto objects = lines_of(fs::path(WBI_LAYERING_DIR) / (target + ".objects"));
  EXPECT_FALSE(objects.empty()) << target << ": no objects listed";
  const auto deps = recorded_dependencies(objects);
  EXPECT_EQ(deps.size(), objects.size()) << target << ": a dependency record per object";
  const fs::path build = wbi::test::binary_dir();
  const fs::path source = fs::weakly_canonical(wbi::test::source_dir());
  const fs::path build_dir = fs::weakly_canonical(build);
  std::vector<std::string> found;
  for (const auto& [object, headers] : deps) {
    // The compiler records the source file first: the record was read.
    const auto source_file = fs::path(object).stem().string();  // e.g. tick_pacer.cpp
    EXPECT_TRUE(
        std::any_of(headers.begin(), headers.end(),
                    [&](const std::string& h) { return fs::path(h).filename() == source_file; }))
        << object << ": " << headers.size() << " dependencies recorded, not its source";
    for (const auto& header : headers) {
      const fs::path path = fs::weakly_canonical(build / header);  // relative: to the build
      // MuJoCo by name, within the tree only below it (the checkout's own folder
      // may well be called after MuJoCo, e.g. a worktree "wt-mujoco").
      const fs::path named = under(path, build_dir) ? path.lexically_relative(build_dir)
                             : under(path, source)  ? path.lexically_relative(source)
                                                    : path;
      if (under(path, source / "robot_side" / "sim") ||
          under(path, source / "components" / "sim_robot") || mentions_mujoco(named.string())) {
        found.push_back(object + " includes " + path.string());
      }
    }
  }
  return found;
}

TEST(DriverLayering, TheDriverLibraryIncludesNoSimulatorHeader) {
  // The control: the simulation component includes the own plant's headers.
  EXPECT_FALSE(simulator_headers("wbi_sim_robot").empty());
  for (const auto& include : simulator_headers("wbi_robot")) {
    ADD_FAILURE() << include;
  }
}

}  // namespace
