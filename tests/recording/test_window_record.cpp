// `wbi record --window` as a process: this test publishes sensor streams at
// 1 kHz and events through EventLog + EventPump (the way components do) and
// reads the files the recorder writes. Overlapping triggers make one file,
// spaced ones one each, events from before the start are no triggers,
// --max-files keeps the newest, the process stays within the memory bound it
// prints, and bad input is one line and exit 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <wbi/msg/sensors.h>
#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/event_pump.hpp>

#include "child_process.hpp"
#include "record_play_support.hpp"
#include "sample_pattern.hpp"
#include "window_file_check.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::EventKind;
using wbi::EventSeverity;
using wbi::test::ChildProcess;

// SensorSamples (32 joints, ~0.8 kB) on wbi/<robot>/sensors every millisecond, from a thread.
class Stream {
 public:
  Stream(wbi::dds::Participant& participant, const std::vector<std::string>& robots) {
    for (const auto& robot : robots) {
      publishers_.emplace_back(std::make_unique<wbi::dds::Publisher<wbi::msg::SensorSample>>(
          participant, "wbi/" + robot + "/sensors", wbi::dds::qos::kStream));
    }
    thread_ = std::thread([this, robots] {
      wbi::msg::SensorSample sample;
      auto next = std::chrono::steady_clock::now();
      for (std::uint64_t seq = 0; !stop_; ++seq) {
        for (std::size_t i = 0; i < robots.size(); ++i) {
          wbi::test::fill_pattern(sample, robots[i], seq);
          publishers_[i]->publish(sample);
        }
        next += 1ms;
        std::this_thread::sleep_until(next);
      }
    });
  }
  ~Stream() {
    stop_ = true;
    thread_.join();
  }

 private:
  std::vector<std::unique_ptr<wbi::dds::Publisher<wbi::msg::SensorSample>>> publishers_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

class WindowRecord : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = wbi::test::scratch_file(
        "window_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  // Emits one event now and puts it on the wire.
  void emit(EventKind kind, const std::string& source) {
    events_.emit(EventSeverity::warning, kind, "from the test", "", "win", source);
    pump_.flush();
  }

  std::unique_ptr<ChildProcess> start_recorder(std::vector<std::string> extra) {
    std::vector<std::string> args = {"record", "-o", directory_.string(), "--probe", "0"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto recorder = std::make_unique<ChildProcess>(wbi::test::wbi_program(), args);
    EXPECT_TRUE(recorder->wait_for_output("recording wbi/events", 20s)) << recorder->output();
    return recorder;
  }

  static std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
      ++n;
    }
    return n;
  }

  // Waits until the recorder has written `files` files in all.
  static bool wait_for_files(ChildProcess& recorder, std::size_t files) {
    const auto deadline = std::chrono::steady_clock::now() + 20s;
    while (count(recorder.output(), "window: wrote ") < files) {
      if (std::chrono::steady_clock::now() > deadline || !recorder.running()) {
        return false;
      }
      std::this_thread::sleep_for(20ms);
    }
    return true;
  }

  std::vector<std::filesystem::path> files_in_directory() const {
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(directory_)) {
      files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
  }

  wbi::dds::Participant participant_{"window_test"};
  wbi::runtime::EventLog events_{{100.0, 100.0}};
  wbi::runtime::EventPump pump_{participant_, events_, "test"};
  std::filesystem::path directory_;
};

const std::vector<EventKind> kTriggers = {EventKind::lifecycle, EventKind::watchdog_trip};

// A window's edges are cut on the recorder's log times. Where nothing else
// holds the stream, a test can only see how far the file reaches: a pause in
// the stream's arrival under load (the stream's thread or the recorder
// descheduled) leaves the first sample inside the window by that pause (a CI
// run met 15 ms). Where two files overlap they hold the same ring records, and
// each edge is checked to the sample against the other file.
constexpr double kUnseenEdgeS = 0.1;
constexpr int kBeforeS = 2;  // the window of the overlapping triggers' test
constexpr int kAfterS = 1;
constexpr std::uint64_t kNsPerS = 1'000'000'000;

TEST_F(WindowRecord, OverlappingTriggersMakeOneFileSpacedOnesAnotherOldEventsNone) {
  Stream stream(participant_, {"win"});
  emit(EventKind::lifecycle, "before_start");  // transient-local: the recorder gets it, late
  auto recorder =
      start_recorder({"--window", std::to_string(kBeforeS) + ":" + std::to_string(kAfterS),
                      "--trigger", "LIFECYCLE,WATCHDOG_TRIP", "wbi/win/sensors"});
  ASSERT_TRUE(recorder->wait_for_output("recording wbi/win/sensors", 20s)) << recorder->output();
  std::this_thread::sleep_for(kBeforeS * 1s + 500ms);  // the window fills before the first trigger

  emit(EventKind::lifecycle, "first");
  std::this_thread::sleep_for(400ms);
  emit(EventKind::watchdog_trip, "second");  // while the first file is open: extends it
  emit(EventKind::parameter_changed, "no_trigger");
  ASSERT_TRUE(wait_for_files(*recorder, 1)) << recorder->output();
  // The second window starts kBeforeS before this, inside the first file (it
  // ended kAfterS after "second").
  emit(EventKind::lifecycle, "third");
  ASSERT_TRUE(wait_for_files(*recorder, 2)) << recorder->output();
  EXPECT_EQ(recorder->stop(SIGINT), 0) << recorder->output();

  const std::string output = recorder->output();
  EXPECT_NE(output.find("3 triggers (1 merged into an open file, 1 from before the start ignored)"),
            std::string::npos)
      << output;
  const auto files = files_in_directory();
  ASSERT_EQ(files.size(), 2u) << output;
  EXPECT_NE(files[0].filename().string().find("_LIFECYCLE.mcap"), std::string::npos);

  const auto first = wbi::test::check_window_file(files[0], "wbi/win/sensors", kTriggers);
  ASSERT_EQ(first.problem, "");
  EXPECT_EQ(first.trigger_sources, (std::vector<std::string>{"first", "second"}));
  EXPECT_EQ(first.events, 3u);  // and the PARAMETER_CHANGED, not the one before the start
  EXPECT_GE(first.before_s, kBeforeS - kUnseenEdgeS);
  EXPECT_LE(first.before_s, kBeforeS + 0.001);
  EXPECT_EQ(first.gaps, 0u);
  // `wbi bag info` lists the file's events: time, severity, source, kind, text.
  const auto info = wbi::test::run_wbi({"bag", "info", files[0].string()});
  EXPECT_EQ(info.code, 0) << info.output;
  EXPECT_NE(info.output.find("events:       3\n"), std::string::npos) << info.output;
  EXPECT_TRUE(std::regex_search(
      info.output, std::regex(R"(UTC  WARNING  second +WATCHDOG_TRIP +from the test\n)")))
      << info.output;
  const auto json = wbi::test::run_wbi({"bag", "info", "--json", files[0].string()});
  EXPECT_NE(json.output.find(R"("kind": "PARAMETER_CHANGED")"), std::string::npos) << json.output;

  const auto second = wbi::test::check_window_file(files[1], "wbi/win/sensors", kTriggers);
  ASSERT_EQ(second.problem, "");
  EXPECT_EQ(second.trigger_sources, (std::vector<std::string>{"third"}));
  EXPECT_GE(second.after_s, kAfterS - kUnseenEdgeS);
  EXPECT_EQ(second.gaps, 0u);

  // The second file begins with the first sample logged at or after its
  // trigger − kBeforeS; the first holds the sample before it, logged earlier.
  const std::uint64_t second_start =
      static_cast<std::uint64_t>(second.first_trigger_ns) - kBeforeS * kNsPerS;
  const wbi::test::StreamSample head = second.stream.front();
  EXPECT_GE(head.log_time, second_start);
  EXPECT_EQ(wbi::test::log_time_of(first, head.seq), head.log_time) << "the same ring record";
  const auto before_head = wbi::test::log_time_of(first, head.seq - 1);
  ASSERT_TRUE(before_head) << "the files do not overlap: the test was held for seconds";
  EXPECT_LT(*before_head, second_start);
  // The first file ends with the last sample logged at or before its last
  // trigger + kAfterS; the second holds the sample after it, logged later.
  const std::uint64_t first_end =
      static_cast<std::uint64_t>(first.last_trigger_ns) + kAfterS * kNsPerS;
  const wbi::test::StreamSample tail = first.stream.back();
  EXPECT_LE(tail.log_time, first_end);
  const auto after_tail = wbi::test::log_time_of(second, tail.seq + 1);
  ASSERT_TRUE(after_tail) << "the files do not overlap: the test was held for seconds";
  EXPECT_GT(*after_tail, first_end);
}

TEST_F(WindowRecord, MaxFilesKeepsTheNewestAndLeavesOtherFilesAlone) {
  Stream stream(participant_, {"win"});
  std::filesystem::create_directories(directory_);
  std::ofstream(directory_ / "mine.mcap") << "not the recorder's";
  auto recorder = start_recorder(
      {"--window", "0.3:0.2", "--trigger", "WATCHDOG_TRIP", "--max-files", "2", "wbi/win/sensors"});
  ASSERT_TRUE(recorder->wait_for_output("recording wbi/win/sensors", 20s)) << recorder->output();
  for (std::size_t i = 1; i <= 4; ++i) {
    std::this_thread::sleep_for(400ms);  // a window's worth before each trigger
    emit(EventKind::watchdog_trip, "trip" + std::to_string(i));
    ASSERT_TRUE(wait_for_files(*recorder, i)) << recorder->output();
  }
  EXPECT_EQ(recorder->stop(SIGINT), 0) << recorder->output();
  EXPECT_EQ(count(recorder->output(), "window: deleted "), 2u) << recorder->output();
  const auto files = files_in_directory();
  ASSERT_EQ(files.size(), 3u) << recorder->output();
  EXPECT_EQ(files[2].filename(), "mine.mcap");
  EXPECT_EQ(wbi::test::check_window_file(files[0], "wbi/win/sensors", kTriggers).trigger_sources,
            (std::vector<std::string>{"trip3"}));
  EXPECT_EQ(wbi::test::check_window_file(files[1], "wbi/win/sensors", kTriggers).trigger_sources,
            (std::vector<std::string>{"trip4"}));
}

long rss_bytes(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kib = 0;
      status >> kib;
      return kib * 1024;
    }
  }
  return -1;
}

// The ring fills and wraps about every 3 s under 2.5 MB/s; a file is written
// while it does. The process's resident memory grows by no more than the
// bound it printed, plus what DDS takes for the readers of the topics it
// discovers after that line (kDdsReaders).
TEST_F(WindowRecord, StaysWithinThePrintedMemoryBound) {
  constexpr long kDdsReaders = 8L << 20;
  Stream stream(participant_, {"win", "win2", "win3"});
  std::vector<std::string> args = {
      "record", "-o",        directory_.string(), "--probe",      "0",   "--window",
      "1:0.5",  "--trigger", "LIFECYCLE",         "--max-memory", "16M", "wbi/win.*/sensors"};
  ChildProcess recorder(wbi::test::wbi_program(), args);
  // std::cerr writes the line in pieces: wait for the byte count, not the line's start.
  ASSERT_TRUE(recorder.wait_for_output(" bytes: ring", 20s)) << recorder.output();
  const long baseline = rss_bytes(recorder.pid());
  std::smatch bound_match;
  const std::string header = recorder.output();
  ASSERT_TRUE(
      std::regex_search(header, bound_match, std::regex(R"(memory bound .* \((\d+) bytes)")))
      << header;
  const long bound = std::stol(bound_match[1]);
  EXPECT_EQ(bound, 16L << 20);
  long peak = baseline;
  const auto start = std::chrono::steady_clock::now();
  bool triggered = false;
  while (std::chrono::steady_clock::now() - start < 10s) {
    peak = std::max(peak, rss_bytes(recorder.pid()));
    if (!triggered && std::chrono::steady_clock::now() - start > 6s) {
      emit(EventKind::lifecycle, "mid_run");
      triggered = true;
    }
    std::this_thread::sleep_for(50ms);
  }
  ASSERT_TRUE(wait_for_files(recorder, 1)) << recorder.output();
  peak = std::max(peak, rss_bytes(recorder.pid()));
  EXPECT_EQ(recorder.stop(SIGINT), 0) << recorder.output();
  const std::string output = recorder.output();
  std::smatch samples;
  ASSERT_TRUE(std::regex_search(output, samples, std::regex(R"((\d+) samples on 4 topics)")))
      << output;
  // Enough went through to fill the ring (6.8 MiB of the 16) twice over.
  EXPECT_GT(std::stol(samples[1]) * 800, 2 * (7L << 20)) << output;
  EXPECT_NE(output.find("evicted inside the window 0, lost to a file 0"), std::string::npos)
      << output;
  std::cout << "recorder RSS: " << baseline / 1024 << " KiB at the start, peak " << peak / 1024
            << " KiB (growth " << (peak - baseline) / 1024 << " KiB, bound " << bound / 1024
            << " KiB)\n";
  EXPECT_LE(peak - baseline, bound + kDdsReaders);
}

TEST_F(WindowRecord, BadInputIsOneLineAndExitOne) {
  const std::string dir = directory_.string();
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"--window", "5:2", "--trigger", "LIFECYCLE,WATCHDOG", "--all"}, "'WATCHDOG'"},
      {{"--window", "5x2", "--trigger", "LIFECYCLE", "--all"}, "'5x2'"},
      {{"--window", "5:-2", "--trigger", "LIFECYCLE", "--all"}, "'5:-2'"},
      {{"--window", "5:2", "--all"}, "--trigger"},
      {{"--trigger", "LIFECYCLE", "--all"}, "--trigger goes with --window"},
      {{"--window", "5:2", "--trigger", "LIFECYCLE", "--max-memory", "1M", "--all"}, "too small"},
      {{"--window", "5:2", "--trigger", "LIFECYCLE", "--max-memory", "lots", "--all"}, "'lots'"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"record", "-o", dir};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const auto run = wbi::test::run_wbi(args);
    EXPECT_EQ(run.code, 1) << run.output;
    EXPECT_EQ(count(run.output, "\n"), 1u) << run.output;
    EXPECT_NE(run.output.find(c.says), std::string::npos) << run.output;
  }
  // Too large for the memory at the rate the topics have: refused with what it needs.
  Stream stream(participant_, {"win"});
  const auto run =
      wbi::test::run_wbi({"record", "-o", dir, "--window", "80000:1", "--trigger", "LIFECYCLE",
                          "--max-memory", "16M", "--probe", "2", "wbi/win/sensors"});
  EXPECT_EQ(run.code, 1) << run.output;
  EXPECT_NE(run.output.find("wbi record: --window 80000:1 needs "), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("more than --max-memory 16.0 MiB"), std::string::npos) << run.output;
}

}  // namespace
