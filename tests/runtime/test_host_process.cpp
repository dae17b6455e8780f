// wbi_host as a process: runs a host file, stops cleanly on SIGTERM (exit 0)
// and SIGINT (exit 130), and rejects a bad file with one line naming it.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

std::filesystem::path host() { return wbi::test::binary_dir() / "bin" / "wbi_host"; }

std::filesystem::path write_file(const std::string& name, const std::string& text) {
  const auto path = wbi::test::binary_dir() / "tests" / name;
  std::ofstream(path) << text;
  return path;
}

TEST(HostProcess, RunsTheFileAndStopsCleanlyOnSigterm) {
  const auto file = write_file("host_idle.yaml",
                               "status_period_s: 0.1\ncomponents:\n"
                               "  - {name: ticker, type: idle, rate_hz: 50}\n");
  wbi::dds::Participant participant("watcher");
  wbi::dds::Subscriber<wbi::msg::ComponentStatus> status(participant, wbi::dds::topics::kStatus,
                                                         wbi::dds::qos::kStatus);
  ChildProcess process(host(), {file.string()});
  ASSERT_TRUE(process.wait_for_output("wbi_host: running 1 component(s)", 20s)) << process.output();
  wbi::dds::Received<wbi::msg::ComponentStatus> got;
  ASSERT_TRUE(status.wait_newer(got, 0, 10s));
  const auto end = std::chrono::steady_clock::now() + 10s;
  while ((got.sample.state() != wbi::msg::ACTIVE || got.sample.iterations() == 0) &&
         std::chrono::steady_clock::now() < end) {
    status.wait_newer(got, got.count, 1s);
  }
  EXPECT_STREQ(got.sample.instance().c_str(), "ticker");
  EXPECT_EQ(got.sample.state(), wbi::msg::ACTIVE);
  EXPECT_EQ(process.stop(SIGTERM, 10s), 0) << process.output();
  EXPECT_NE(process.output().find("wbi_host: stopped (SIGTERM)"), std::string::npos)
      << process.output();
}

TEST(HostProcess, SigintExitsWith130) {
  const auto file = write_file("host_idle2.yaml", "components:\n  - {name: a, type: idle}\n");
  ChildProcess process(host(), {file.string()});
  ASSERT_TRUE(process.wait_for_output("wbi_host: running", 20s)) << process.output();
  EXPECT_EQ(process.stop(SIGINT, 10s), 130) << process.output();
}

TEST(HostProcess, BadFileIsOneLineNamingFileAndLine) {
  const auto file =
      write_file("host_bad.yaml", "components:\n  - name: a\n    type: idle\n    rat_hz: 5\n");
  ChildProcess process(host(), {file.string()});
  const auto code = process.wait(20s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 78);  // a configuration error: `wbi launch` does not respawn it
  EXPECT_NE(process.output().find("wbi_host: configuration error: " + file.string() +
                                  ":4: component: unknown key 'rat_hz'"),
            std::string::npos)
      << process.output();
  ChildProcess missing(host(), {"/nonexistent/robot.yaml"});
  ASSERT_EQ(missing.wait(20s), 78);
  EXPECT_NE(missing.output().find("/nonexistent/robot.yaml: cannot read the host file"),
            std::string::npos);
}

}  // namespace
