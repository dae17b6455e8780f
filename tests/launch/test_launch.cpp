// `wbi launch` with real processes: start order by readiness, prefixed
// output, summary line, respawn, failure of a required process, duration,
// Ctrl-C, and SIGKILL of a process that ignores SIGTERM.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

class LaunchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("wbi_launch_test_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto path = dir_ / name;
    std::ofstream(path) << text;
    return path;
  }

  static std::filesystem::path wbi_exe() { return wbi::test::binary_dir() / "bin" / "wbi"; }
  static std::string talker() {
    return (wbi::test::binary_dir() / "tests" / "wbi_test_talker").string();
  }

  std::filesystem::path dir_;
};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::string last_line(const std::string& text) {
  auto end = text.find_last_not_of('\n');
  auto start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1,
                     end - (start == std::string::npos ? 0 : start + 1) + 1);
}

TEST_F(LaunchTest, StartsByReadinessPrefixesOutputAndEndsWithTheSummary) {
  const auto deploy =
      write("ok.yaml",
            "summary: {process: listener, match: \"seq:\"}\n"
            "processes:\n"
            "  - name: talker\n"
            "    command: [" +
                talker() +
                ", launchtest, \"0\"]\n"
                "  - name: listener\n"
                "    command: [wbi, topic, echo, wbi/launchtest/sensors, --count, \"3\"]\n"
                "    wait_for: {topics: [wbi/launchtest/sensors], timeout: 20}\n"
                "    shutdown_on_exit: true\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string()});
  const auto code = launch.wait(90s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  const std::string out = launch.output();
  EXPECT_EQ(*code, 0) << out;
  EXPECT_TRUE(contains(out, "[launch] listener: waiting for wbi/launchtest/sensors")) << out;
  EXPECT_LT(out.find("[launch] talker: started"), out.find("[launch] listener: started")) << out;
  EXPECT_TRUE(contains(out, "[talker] talker: ready")) << out;
  EXPECT_TRUE(contains(out, "[listener]   seq: ")) << out;
  EXPECT_TRUE(contains(out, "talker: stopped")) << out;
  EXPECT_EQ(last_line(out).rfind("  seq: ", 0), 0u) << "last line: '" << last_line(out) << "'";
}

TEST_F(LaunchTest, RespawnsThenFailsWhenARequiredProcessKeepsFailing) {
  const auto deploy = write("fail.yaml",
                            "processes:\n"
                            "  - name: flaky\n"
                            "    command: [sh, -c, \"echo run; exit 3\"]\n"
                            "    respawn: {enabled: true, delay: 0.05, max_retries: 2}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string()});
  const auto code = launch.wait(60s);
  ASSERT_TRUE(code.has_value());
  const std::string out = launch.output();
  EXPECT_EQ(*code, 1) << out;
  std::size_t runs = 0;
  for (auto at = out.find("[flaky] run"); at != std::string::npos;
       at = out.find("[flaky] run", at + 1)) {
    ++runs;
  }
  EXPECT_EQ(runs, 3u) << out;
  EXPECT_TRUE(contains(out, "flaky: failed with exit code 3")) << out;
  EXPECT_TRUE(contains(out, "flaky: exit code 3, 2 restart(s)")) << out;
}

// An optional process's failure does not stop the launch, but the launch's
// exit code and summary still say it (a script must not read success).
TEST_F(LaunchTest, OptionalProcessFailureDoesNotStopTheLaunchButFailsIt) {
  const auto deploy = write("optional.yaml",
                            "processes:\n"
                            "  - {name: helper, command: [sh, -c, \"exit 5\"], required: false}\n"
                            "  - {name: sleeper, command: [sleep, \"30\"]}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "1.5"});
  const auto code = launch.wait(60s);
  ASSERT_TRUE(code.has_value());
  const std::string out = launch.output();
  EXPECT_EQ(*code, 1) << out;
  EXPECT_TRUE(contains(out, "duration of 1.5")) << out;
  EXPECT_TRUE(contains(out, "sleeper: stopped")) << out;
  EXPECT_TRUE(contains(out, "  helper: exit code 5: FAILED, ended in error\n")) << out;
  EXPECT_TRUE(contains(out, "  sleeper: stopped (exit code 143)\n")) << out;
}

// A configuration error (exit code 78: here a parameter the component does not
// know, then a type no plugin registers) cannot heal: the process is not
// respawned, whatever its policy, and the launch fails naming it.
TEST_F(LaunchTest, ConfigurationErrorIsNotRespawned) {
  for (const std::string component : {"{name: idle_bad, type: idle, parameters: {bogus: 1}}",
                                      "{name: idle_bad, type: no_such}"}) {
    const auto deploy = write("config_error.yaml",
                              "processes:\n"
                              "  - name: host\n"
                              "    components: [" +
                                  component +
                                  "]\n"
                                  "    respawn: {enabled: true, delay: 0.05, max_retries: 3}\n");
    ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "30"});
    const auto code = launch.wait(60s);
    ASSERT_TRUE(code.has_value()) << launch.output();
    const std::string out = launch.output();
    EXPECT_EQ(*code, 1) << out;
    EXPECT_TRUE(contains(out, "[host] wbi_host: configuration error: ")) << out;
    EXPECT_TRUE(contains(out, "host: failed with exit code 78 (configuration error)")) << out;
    EXPECT_TRUE(contains(out, "host: not respawned")) << out;
    EXPECT_FALSE(contains(out, "respawn 1 of 3")) << out;
    EXPECT_TRUE(contains(out, "  host: exit code 78: FAILED, configuration error\n")) << out;
  }
}

TEST_F(LaunchTest, CtrlCStopsEverything) {
  const auto deploy =
      write("sigint.yaml", "processes:\n  - {name: sleeper, command: [sleep, \"30\"]}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string()});
  ASSERT_TRUE(launch.wait_for_output("sleeper: started", 30s)) << launch.output();
  kill(launch.pid(), SIGINT);
  const auto code = launch.wait(30s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  EXPECT_EQ(*code, 130) << launch.output();
  EXPECT_TRUE(contains(launch.output(), "interrupted (SIGINT)")) << launch.output();
}

// Into a pipe (this test's, `| tee`, a supervisor) a process's lines come out
// as they are printed, not when the launcher's buffer fills or the launch ends.
TEST_F(LaunchTest, OutputReachesAPipeWhileTheLaunchRuns) {
  const auto deploy =
      write("pipe.yaml",
            "processes:\n"
            "  - {name: chatty, command: [sh, -c, \"echo first line; sleep 30\"]}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string()});
  EXPECT_TRUE(launch.wait_for_output("[chatty] first line\n", 10s)) << launch.output();
  EXPECT_EQ(launch.stop(SIGINT, 10s), 130) << launch.output();
}

// Running, or a zombie nobody reaps (the launcher that would is gone).
bool running(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string skip;
  char state = 0;
  return stat >> skip >> skip >> state && state != 'Z';
}

// A launcher killed outright (SIGKILL: no chance to stop anything) still takes
// its component processes with it: no controller outlives its supervisor.
TEST_F(LaunchTest, ComponentsStopWhenTheLauncherIsKilled) {
  const auto deploy = write("orphans.yaml",
                            "processes:\n"
                            "  - {name: host, components: [{name: idle, type: idle}]}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string()});
  ASSERT_TRUE(launch.wait_for_output("wbi_host: running", 30s)) << launch.output();
  const std::string marker = "host: started (pid ";
  const auto at = launch.output().find(marker);
  ASSERT_NE(at, std::string::npos) << launch.output();
  const pid_t host = std::stoi(launch.output().substr(at + marker.size()));
  ASSERT_TRUE(running(host));
  launch.stop(SIGKILL);
  const auto deadline = std::chrono::steady_clock::now() + 10s;
  while (running(host) && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);  // polling another process's state: nothing to wait on
  }
  EXPECT_FALSE(running(host)) << "wbi_host (pid " << host << ") outlived its launcher";
  if (running(host)) {
    kill(host, SIGKILL);
  }
}

// The pid `wbi launch` printed for process `name` (its n-th start, from 1).
pid_t started_pid(const std::string& output, const std::string& name, int nth = 1) {
  const std::string marker = "[launch] " + name + ": started (pid ";
  std::size_t at = std::string::npos;
  for (int k = 0; k < nth; ++k) {
    at = output.find(marker, at == std::string::npos ? 0 : at + 1);
    if (at == std::string::npos) {
      return -1;
    }
  }
  return std::stoi(output.substr(at + marker.size()));
}

// A process stopped without dying (SIGSTOP: as a deadlock looks from outside)
// sends no status heartbeat: the launch says so within its hang_timeout and
// applies its respawn policy (killed and started again).
TEST_F(LaunchTest, HungProcessIsDetectedAndRespawned) {
  const auto deploy = write("hang.yaml",
                            "processes:\n"
                            "  - name: host\n"
                            "    components: [{name: idle_hang, type: idle}]\n"
                            "    hang_timeout: 2.5\n"
                            "    respawn: {enabled: true, delay: 0.1, max_retries: 1}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "60"});
  ASSERT_TRUE(launch.wait_for_output("host: heartbeat heard", 30s)) << launch.output();
  const pid_t host = started_pid(launch.output(), "host");
  ASSERT_GT(host, 0) << launch.output();
  kill(host, SIGSTOP);
  ASSERT_TRUE(launch.wait_for_output("host: no status heartbeat from its components", 30s))
      << launch.output();
  ASSERT_TRUE(launch.wait_for_output("host: respawn 1 of 1", 10s)) << launch.output();
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (started_pid(launch.output(), "host", 2) < 0 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);  // polling the launch's output for its second start
  }
  ASSERT_GT(started_pid(launch.output(), "host", 2), 0) << launch.output();
  EXPECT_NE(started_pid(launch.output(), "host", 2), host);
  launch.stop(SIGINT);
  const auto code = launch.wait(30s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  EXPECT_EQ(*code, 130) << launch.output();
}

// The same without respawn: a required process that hangs fails the launch.
TEST_F(LaunchTest, HungRequiredProcessFailsTheLaunch) {
  const auto deploy = write("hang_required.yaml",
                            "processes:\n"
                            "  - name: host\n"
                            "    components: [{name: idle_required, type: idle}]\n"
                            "    hang_timeout: 2.5\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "60"});
  ASSERT_TRUE(launch.wait_for_output("host: heartbeat heard", 30s)) << launch.output();
  const pid_t host = started_pid(launch.output(), "host");
  ASSERT_GT(host, 0) << launch.output();
  kill(host, SIGSTOP);
  const auto code = launch.wait(40s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  EXPECT_EQ(*code, 1) << launch.output();
  EXPECT_TRUE(contains(launch.output(), "host is required: stopping the launch"))
      << launch.output();
  EXPECT_FALSE(running(host)) << "the stopped process was left behind";
}

// A deadlock in a component's loop leaves its status thread running: the
// heartbeat goes on, the iteration count it carries stops. The launch says
// which loop stopped, after its hang_timeout, and respawns the process; a
// periodic component beside it that keeps looping (idle) is not blamed.
TEST_F(LaunchTest, DeadlockedLoopIsDetectedAndRespawned) {
  const auto host = (wbi::test::binary_dir() / "tests" / "wbi_test_deadlock_host").string();
  const auto deploy = write("deadlock.yaml",
                            "processes:\n"
                            "  - name: busy\n"
                            "    components: [{name: busy_idle, type: idle, rate_hz: 100}]\n"
                            "    hang_timeout: 2.5\n"
                            "  - name: host\n"
                            "    host: " +
                                host +
                                "\n"
                                "    components:\n"
                                "      - {name: stuck, type: deadlock, rate_hz: 100,\n"
                                "         parameters: {after_s: 1.5}}\n"
                                "    hang_timeout: 2.5\n"
                                "    respawn: {enabled: true, delay: 0.1, max_retries: 1}\n"
                                "    required: false\n");  // its second start deadlocks too
  ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "60", "--grace", "1"});
  ASSERT_TRUE(launch.wait_for_output("host: heartbeat heard", 30s)) << launch.output();
  const pid_t first = started_pid(launch.output(), "host");
  ASSERT_GT(first, 0) << launch.output();
  ASSERT_TRUE(launch.wait_for_output("host: the loop of 'stuck' stopped at iteration", 30s))
      << launch.output();
  ASSERT_TRUE(launch.wait_for_output("host: respawn 1 of 1", 10s)) << launch.output();
  const auto deadline = std::chrono::steady_clock::now() + 20s;
  while (started_pid(launch.output(), "host", 2) < 0 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(20ms);  // polling the launch's output for its second start
  }
  EXPECT_GT(started_pid(launch.output(), "host", 2), 0) << launch.output();
  EXPECT_FALSE(running(first)) << "the deadlocked process was left behind";
  EXPECT_FALSE(contains(launch.output(), "busy: the loop of")) << launch.output();
  EXPECT_FALSE(contains(launch.output(), "busy: no status heartbeat")) << launch.output();
  launch.stop(SIGINT);
  const auto code = launch.wait(30s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  EXPECT_EQ(*code, 130) << launch.output();
}

// A shutdown_on_exit process that fails is respawned when its policy allows;
// its clean exit then ends the launch (an experiment's controller that crashed).
TEST_F(LaunchTest, FailedShutdownOnExitProcessIsRespawnedFirst) {
  const auto marker = dir_ / "failed_once";
  const auto deploy = write("shutdown_respawn.yaml",
                            "processes:\n"
                            "  - name: run\n"
                            "    command: [sh, -c, \"if [ -e " +
                                marker.string() +
                                " ]; then echo second; exit 0; fi; "
                                "touch " +
                                marker.string() +
                                "; exit 3\"]\n"
                                "    shutdown_on_exit: true\n"
                                "    respawn: {enabled: true, delay: 0.1, max_retries: 2}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "60"});
  const auto code = launch.wait(30s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  EXPECT_EQ(*code, 0) << launch.output();
  EXPECT_TRUE(contains(launch.output(), "run: failed with exit code 3")) << launch.output();
  EXPECT_TRUE(contains(launch.output(), "run: respawn 1 of 2")) << launch.output();
  EXPECT_TRUE(contains(launch.output(), "[run] second")) << launch.output();
  EXPECT_TRUE(contains(launch.output(), "run ended: stopping the launch")) << launch.output();
}

// A process whose start stalled (exit 75: wbi_host's secured start-up,
// wbi/runtime/handshake_watch.hpp) is started again at once, without a
// respawn policy, 3 times at most; a later good run makes a good launch.
TEST_F(LaunchTest, StalledStartIsStartedAgain) {
  const auto counter = dir_ / "starts";
  const std::string command = "echo x >> " + counter.string() + "; [ $(wc -l < " +
                              counter.string() + ") -le STALLS ] && exit 75; echo ran; sleep 30";
  for (const int stalls : {2, 4}) {
    std::filesystem::remove(counter);
    std::string script = command;
    script.replace(script.find("STALLS"), 6, std::to_string(stalls));
    const auto deploy = write(
        "stall.yaml", "processes:\n  - {name: peer, command: [sh, -c, \"" + script + "\"]}\n");
    ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "2"});
    const auto code = launch.wait(60s);
    ASSERT_TRUE(code.has_value()) << launch.output();
    const std::string out = launch.output();
    EXPECT_TRUE(contains(out, "peer: its start stalled (exit code 75): starting it again, 1 of 3"))
        << out;
    if (stalls == 2) {
      EXPECT_EQ(*code, 0) << out;
      EXPECT_TRUE(contains(out, "[peer] ran")) << out;
      EXPECT_TRUE(contains(out,
                           "  peer: stopped (exit code 143), started again after 2 stalled "
                           "start(s)\n"))
          << out;
    } else {  // 1 start and 3 more, all stalled
      EXPECT_EQ(*code, 1) << out;
      EXPECT_FALSE(contains(out, "[peer] ran")) << out;
      EXPECT_TRUE(contains(out, "FAILED, its start stalled every time")) << out;
    }
  }
}

TEST_F(LaunchTest, ProcessIgnoringSigtermIsKilled) {
  const auto deploy =
      write("stubborn.yaml",
            "processes:\n"
            "  - {name: stubborn, command: [sh, -c, \"trap '' TERM; echo armed; sleep 30\"]}\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string(), "--duration", "1", "--grace", "0.5"});
  const auto code = launch.wait(60s);
  ASSERT_TRUE(code.has_value()) << launch.output();
  EXPECT_EQ(*code, 1) << launch.output();  // a process that must be killed did not stop cleanly
  EXPECT_TRUE(contains(launch.output(), "stubborn: did not stop within")) << launch.output();
  EXPECT_TRUE(contains(launch.output(), "FAILED, did not stop within the grace period: SIGKILL"))
      << launch.output();
}

TEST_F(LaunchTest, BadDeployFileFailsWithItsName) {
  const auto deploy = write("bad.yaml", "processes: 3\n");
  ChildProcess launch(wbi_exe(), {"launch", deploy.string()});
  const auto code = launch.wait(30s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 1);
  EXPECT_TRUE(contains(launch.output(), "bad.yaml:1: processes: expected a non-empty list"))
      << launch.output();
}

// The join flags of `wbi launch` reach every process it starts, above the
// deploy file's domain and the environment (dds/README.md, "Joining a deployment").
TEST_F(LaunchTest, JoinFlagsReachEveryProcess) {
  const auto deploy = write("joined.yaml",
                            "domain_id: 3\n"
                            "processes:\n"
                            "  - name: shower\n"
                            "    command: [sh, -c, \"echo joined $WBI_DOMAIN_ID $WBI_DDS_DISCOVERY "
                            "$WBI_DDS_PEERS ${WBI_DDS_SECURITY_IDENTITY:-none}\"]\n"
                            "    required: false\n");
  ChildProcess launch(wbi_exe(),
                      {"launch", deploy.string(), "--duration", "1", "--domain", "7", "--peers",
                       "10.9.0.1,10.9.0.2"},
                      {"WBI_DOMAIN_ID=5", "WBI_DDS_SECURITY_IDENTITY=someone"});
  const auto code = launch.wait(60s);
  ASSERT_TRUE(code.has_value());
  const std::string out = launch.output();
  // Each process's identity is its own name: the variable is not passed on.
  EXPECT_TRUE(contains(out, "joined 7 peers 10.9.0.1,10.9.0.2 none")) << out;
}

}  // namespace
