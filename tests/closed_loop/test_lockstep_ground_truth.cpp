// Reproducible lockstep, kept: the lockstep demo (deploy/demo_lockstep.yaml:
// robot, estimator and controller in three processes, the controller on its
// clock at 2 kHz, here moving to its target over 1 s) runs twice for 2 s of
// simulated time, its robot writing every tick's ground truth to a file
// (ground_truth_file), and the two files must hold the same samples byte for
// byte: DDS timing (start-up, which process runs when, which sample meets
// which) must not reach the result. `wbi bag compare` names the first tick and
// quantity that differ; that it finds one is checked on a copy of a run with
// one joint's position at one tick changed by one ulp.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <wbi/msg/sensorsPubSubTypes.h>
#include <wbi/dds/cdr.hpp>
#include <wbi/mcap/reader.hpp>
#include <wbi/mcap/writer.hpp>
#include <wbi/msg/idl_text.hpp>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}

// deploy/demo_lockstep.yaml with absolute paths, 2 s long, its ground truth to `recording`.
fs::path deploy_file(const fs::path& recording, int run) {
  const fs::path deploy = wbi::test::source_dir() / "deploy";
  std::ifstream in(deploy / "demo_lockstep.yaml");
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  replace_all(text, "config: robots/", "config: " + (deploy / "robots").string() + "/");
  replace_all(text, "urdf: ../models/",
              "urdf: " + (wbi::test::source_dir() / "models").string() + "/");
  const std::string duration = "duration_s: 3}";
  EXPECT_NE(text.find(duration), std::string::npos) << "deploy/demo_lockstep.yaml changed";
  replace_all(text, duration, "duration_s: 2, ground_truth_file: " + recording.string() + "}");
  // A reference that moves with the robot's time: a cycle on the controller's
  // clock that read one tick's time and the next tick's state would change
  // the command (it did, in 2 of 2 pairs of runs, before the host skipped
  // cycles for states it answered already).
  const std::string last_parameter = "max_age_s: 1.0\n";
  EXPECT_NE(text.find(last_parameter), std::string::npos) << "deploy/demo_lockstep.yaml changed";
  replace_all(text, last_parameter, last_parameter + "          transition_s: 1\n");
  const fs::path out = wbi::test::binary_dir() / "tests" /
                       ("lockstep_ground_truth_" + std::to_string(run) + ".yaml");
  std::ofstream(out) << text;
  return out;
}

// One run: launched, stopped once the robot stepped its last tick; its ground truth file.
fs::path run_demo(int run) {
  const fs::path recording = wbi::test::binary_dir() / "tests" /
                             ("lockstep_ground_truth_" + std::to_string(run) + ".mcap");
  fs::remove(recording);
  const auto start = std::chrono::steady_clock::now();
  wbi::test::ChildProcess launch(
      wbi::test::binary_dir() / "bin" / "wbi",
      {"launch", deploy_file(recording, run).string(), "--duration", "40"});
  EXPECT_TRUE(launch.wait_for_output("duration_s 2 reached: stopped stepping", 40s))
      << launch.output();
  launch.stop(SIGINT, 10s);  // the file is complete once stepping ended
  const std::string out = launch.output();
  EXPECT_EQ(out.find("not answered"), std::string::npos) << "a lockstep tick timed out:\n" << out;
  std::printf("run %d: %.1f s wall\n", run,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return recording;
}

struct Compared {
  int code = -1;
  std::string output;
};

Compared compare(const fs::path& a, const fs::path& b) {
  wbi::test::ChildProcess child(wbi::test::binary_dir() / "bin" / "wbi",
                                {"bag", "compare", a.string(), b.string()});
  const auto code = child.wait(30s);
  return {code.value_or(-1), child.output()};
}

// A copy of `from` with joint 2's position at message `index` one ulp higher.
void write_changed_copy(const fs::path& from, const fs::path& to, std::size_t index) {
  const wbi::mcap::Reader reader(from);
  wbi::mcap::Writer writer(to);
  std::uint16_t channel = 0;
  std::size_t i = 0;
  auto cursor = reader.messages(wbi::mcap::Order::file);
  while (const auto* m = cursor.next()) {
    if (channel == 0) {
      const auto schema = writer.add_schema(m->schema->name, m->schema->encoding, m->schema->data);
      channel = writer.add_channel(schema, m->channel->topic);
    }
    std::vector<std::uint8_t> data(m->data.begin(), m->data.end());
    if (i++ == index) {
      wbi::msg::GroundTruth truth;
      ASSERT_TRUE(wbi::dds::decode_cdr(m->data, truth));
      truth.q()[2] = std::nextafter(truth.q()[2], std::numeric_limits<double>::infinity());
      data = wbi::dds::encode_cdr(truth);
    }
    writer.write(channel, m->sequence, m->log_time, m->publish_time, data);
  }
  writer.close();
}

TEST(LockstepGroundTruth, TwoRunsOfTheDemoRecordTheSameSamples) {
  const fs::path first = run_demo(1);
  const fs::path second = run_demo(2);
  ASSERT_TRUE(fs::exists(first) && fs::exists(second));
  const Compared same = compare(first, second);
  EXPECT_EQ(same.code, 0) << "two lockstep runs differ:\n" << same.output;
  // 2 s of ticks at 1 ms, every one recorded.
  EXPECT_NE(same.output.find("identical: 2000 messages on 1 topic(s)"), std::string::npos)
      << same.output;

  const fs::path changed = wbi::test::binary_dir() / "tests" / "lockstep_ground_truth_changed.mcap";
  write_changed_copy(first, changed, 1234);
  const Compared other = compare(first, changed);
  EXPECT_EQ(other.code, 1) << other.output;
  EXPECT_NE(other.output.find("wbi/arm/ground_truth: message 1234 (tick 1234, t = "),
            std::string::npos)
      << other.output;
  EXPECT_NE(other.output.find("): q[2]: "), std::string::npos) << other.output;
  for (const auto& file : {first, second, changed}) {
    fs::remove(file);
  }
}

}  // namespace
