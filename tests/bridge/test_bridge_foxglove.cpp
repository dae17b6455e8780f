// `wbi bridge` against Foxglove's own client: the demo (deploy/demo.yaml) runs,
// `wbi bridge --port 0` serves it over the Foxglove WebSocket protocol, and
// foxglove_client_check.js (beside this file) connects with
// @foxglove/ws-protocol and decodes with @foxglove/omgidl-serialization, given
// only what the bridge advertises: the channels and their IDL, encoders
// against ground truth, the frame transforms, the controller's parameters
// (set, refused, a new target reached), and a stalled second client that
// does not slow the first. Needs node, npm and the packages in wbi's npm
// cache (scripts/install-deps; the test stays offline): when one is missing
// the test is skipped with the reason, never failed.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <system_error>
#include <thread>

#include <unistd.h>

#include "../recording/npm_packages.hpp"
#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

constexpr const char* kListening = "wbi bridge: listening on ";

// The npm packages and the script's copy, removed however the test ends.
struct ScratchDir {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("wbi_bridge_foxglove_" + std::to_string(::getpid()));
  ScratchDir() { std::filesystem::create_directories(path); }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
};

// The URL of the bridge's "listening on ws://..." line, once the whole line
// is out; nullopt when it does not come within `timeout` or the bridge exits.
std::optional<std::string> listening_url(ChildProcess& bridge, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline && bridge.running()) {
    const std::string out = bridge.output();
    const auto at = out.find(kListening);
    const auto end = at == std::string::npos ? at : out.find('\n', at);
    if (end != std::string::npos) {
      const auto begin = at + std::string(kListening).size();
      const std::string rest = out.substr(begin, end - begin);
      return rest.substr(0, rest.find_first_of(" \t\r"));
    }
    std::this_thread::sleep_for(50ms);
  }
  return std::nullopt;
}

TEST(BridgeFoxglove, FoxglovesClientDecodesStreamsAndSetsParameters) {
  const ScratchDir scratch;
  const auto npm = wbi::test::install_npm_packages(
      scratch.path, {"@foxglove/ws-protocol@^0.8", "ws@^8", "@foxglove/omgidl-parser@^1",
                     "@foxglove/omgidl-serialization@^1"});
  if (npm.node.empty()) {
    GTEST_SKIP() << npm.skip_reason;
  }
  // Beside its node_modules, so that node resolves the packages from there.
  const auto script = scratch.path / "foxglove_client_check.js";
  std::filesystem::copy_file(
      wbi::test::source_dir() / "tests" / "bridge" / "foxglove_client_check.js", script,
      std::filesystem::copy_options::overwrite_existing);

  const auto wbi = wbi::test::binary_dir() / "bin" / "wbi";
  ChildProcess launch(wbi, {"launch", (wbi::test::source_dir() / "deploy" / "demo.yaml").string(),
                            "--duration", "40"});
  ChildProcess bridge(wbi, {"bridge", "--port", "0"});
  const auto url = listening_url(bridge, 30s);
  ASSERT_TRUE(url.has_value()) << "no \"" << kListening << "\" line\n"
                               << bridge.output() << "\n--- launch:\n"
                               << launch.output();

  ChildProcess check(npm.node, {script.string(), *url,
                                (wbi::test::source_dir() / "models" / "arm7.urdf").string()});
  const auto code = check.wait(120s);
  std::cout << check.output();
  EXPECT_EQ(code, std::optional<int>(0))
      << (code ? "" : "the check did not end within 120 s\n") << "--- bridge:\n"
      << bridge.output() << "\n--- launch:\n"
      << launch.output();

  const int bridge_code = bridge.stop(SIGINT, 10s);
  launch.stop(SIGINT, 20s);
  EXPECT_EQ(bridge_code, 0) << "the bridge on SIGINT\n" << bridge.output();
}

}  // namespace
