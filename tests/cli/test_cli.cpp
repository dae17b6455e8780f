// The `wbi` command line as a user meets it: help that teaches (verbs by task,
// examples), version, exit codes, clear errors, `wbi topic list|echo` against
// a real publisher process, and `wbi controller`/`wbi param` finding the only
// robot with a controller host on the domain.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;

struct Run {
  int code;
  std::string output;
};

Run wbi_cli(const std::vector<std::string>& args, std::chrono::milliseconds timeout = 30s) {
  ChildProcess process(wbi::test::binary_dir() / "bin" / "wbi", args);
  const auto code = process.wait(timeout);
  return {code.value_or(-1), process.output()};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
  }
  return lines;
}

// The verbs `wbi --help` lists (the verb table): the first word of each line
// indented by two spaces.
std::vector<std::string> listed_verbs(const std::string& help) {
  std::vector<std::string> verbs;
  for (const auto& line : lines_of(help)) {
    if (line.size() > 2 && line.rfind("  ", 0) == 0 && line[2] != ' ') {
      verbs.push_back(line.substr(2, line.find(' ', 2) - 2));
    }
  }
  return verbs;
}

TEST(Cli, HelpListsEveryVerb) {
  const auto run = wbi_cli({"--help"});
  EXPECT_EQ(run.code, 0);
  for (const char* verb : {"launch", "topic", "events", "bridge", "controller", "param", "record",
                           "play", "bag", "render", "model", "estimate", "robot", "plugins"}) {
    EXPECT_TRUE(contains(run.output, std::string("\n  ") + verb + " ")) << verb << "\n"
                                                                        << run.output;
  }
}

// `wbi --help` groups the verbs by task, each with its help and under it an
// example naming it; it fits a screen (40 lines of at most 100 columns).
TEST(Cli, HelpGroupsTheVerbsByTaskWithAnExampleEach) {
  const auto run = wbi_cli({"--help"});
  ASSERT_EQ(run.code, 0) << run.output;
  const auto lines = lines_of(run.output);
  EXPECT_LE(lines.size(), 40u) << run.output;
  std::vector<std::string> headings;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_LE(lines[i].size(), 100u) << lines[i];
    if (i > 2 && !lines[i].empty() && lines[i][0] != ' ') {
      headings.push_back(lines[i].substr(0, lines[i].find(':')));
    }
    if (lines[i].size() > 2 && lines[i].rfind("  ", 0) == 0 && lines[i][2] != ' ') {
      const std::string verb = lines[i].substr(2, lines[i].find(' ', 2) - 2);
      ASSERT_LT(i + 1, lines.size());
      EXPECT_TRUE(contains(lines[i + 1], "  wbi " + verb + " "))
          << "the example of " << verb << ": " << lines[i + 1];
    }
  }
  EXPECT_EQ(headings,
            (std::vector<std::string>{"run", "watch", "control", "record", "model", "robot"}))
      << run.output;
  EXPECT_EQ(listed_verbs(run.output).size(), 14u) << run.output;
}

// `wbi WORDS --help` exits 0 and ends with an "Example:"/"Examples:" section
// whose last command names `wbi WORDS`. Returns the help.
std::string expect_help_ends_with_example(const std::vector<std::string>& words) {
  std::string command = "wbi";
  for (const auto& word : words) {
    command += " " + word;
  }
  auto args = words;
  args.push_back("--help");
  const auto run = wbi_cli(args);
  EXPECT_EQ(run.code, 0) << command << " --help:\n" << run.output;
  const auto section = run.output.rfind("\nExample");
  EXPECT_NE(section, std::string::npos) << command << " --help has no examples:\n" << run.output;
  if (section == std::string::npos) {
    return run.output;
  }
  const auto examples = lines_of(run.output.substr(section + 1));
  for (std::size_t i = 1; i < examples.size(); ++i) {
    EXPECT_EQ(examples[i].rfind("  ", 0), 0u)
        << command << " --help: the examples are not its last section:\n"
        << run.output;
  }
  EXPECT_TRUE(contains(examples.back(), command + " ") || examples.back().ends_with(command))
      << command << " --help does not end with an example of it:\n"
      << run.output;
  return run.output;
}

// Every verb of the table, and every sub-command of those that have some
// (`usage: wbi VERB {a,b,c}`), ends its --help with an example of itself.
TEST(Cli, EveryVerbsHelpEndsWithAnExample) {
  const auto verbs = listed_verbs(wbi_cli({"--help"}).output);
  ASSERT_FALSE(verbs.empty());
  for (const auto& verb : verbs) {
    const std::string help = expect_help_ends_with_example({verb});
    const std::string usage = "usage: wbi " + verb + " {";
    if (help.rfind(usage, 0) != 0) {
      continue;
    }
    const auto end = help.find('}');
    std::istringstream names(help.substr(usage.size(), end - usage.size()));
    for (std::string sub; std::getline(names, sub, ',');) {
      expect_help_ends_with_example({verb, sub});
    }
  }
}

TEST(Cli, NoVerbPrintsHelpAndFails) {
  const auto run = wbi_cli({});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "usage: wbi")) << run.output;
}

TEST(Cli, VersionIsPrinted) {
  const auto run = wbi_cli({"--version"});
  EXPECT_EQ(run.code, 0);
  EXPECT_TRUE(contains(run.output, "wbi 0.")) << run.output;
}

TEST(Cli, UnknownVerbFailsWithMessage) {
  const auto run = wbi_cli({"frobnicate"});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "unknown verb 'frobnicate'")) << run.output;
}

// `wbi robot check`: a valid file is summarised; an error is the parser's one line, exit 1.
TEST(Cli, RobotCheck) {
  const auto file = wbi::test::source_dir() / "deploy" / "robots" / "humanoid.yaml";
  const auto ok = wbi_cli({"robot", "check", file.string()});
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_TRUE(contains(ok.output, "humanoid.yaml: valid")) << ok.output;
  EXPECT_TRUE(contains(ok.output, "force_torque: 2")) << ok.output;
  const auto bad = wbi::test::binary_dir() / "tests" / "cli_bad_robot.yaml";
  std::ofstream(bad) << "urdf: " << wbi::test::project_model("humanoid.urdf").string()
                     << "\nimus: [{name: imu, frame: imu_fram}]\n";
  const auto run = wbi_cli({"robot", "check", bad.string()});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output,
                       "cli_bad_robot.yaml:2: imus[0].frame: unknown link or frame "
                       "'imu_fram'"))
      << run.output;
}

// `wbi launch FILE --list`: what scripts take from a deploy file, through its
// one reader (scripts/wbi-security-setup); a bad file is its usual error.
TEST(Cli, LaunchListsTheProcessesOfADeployFile) {
  const auto demo =
      wbi_cli({"launch", (wbi::test::source_dir() / "deploy" / "demo.yaml").string(), "--list"});
  EXPECT_EQ(demo.code, 0) << demo.output;
  EXPECT_EQ(lines_of(demo.output),
            (std::vector<std::string>{"robot\tsim_robot\tarm", "estimator\testimator\tarm",
                                      "model_service\tmodel_service\tarm",
                                      "controller\tpd_gravity\tarm"}))
      << demo.output;
  const auto bad = wbi::test::binary_dir() / "tests" / "cli_bad_deploy.yaml";
  std::ofstream(bad) << "processes:\n  - {name: a, components: [{type: sim_robot}]}\n"
                     << "  - {name: a, command: [true]}\n";
  const auto run = wbi_cli({"launch", bad.string(), "--list"});
  EXPECT_EQ(run.code, 1) << run.output;
  EXPECT_TRUE(contains(run.output, "cli_bad_deploy.yaml:")) << run.output;
}

// `wbi events`: an unknown kind or severity is one line naming it, exit 1,
// before any DDS.
TEST(Cli, EventsNamesABadKindOrSeverity) {
  const auto kind = wbi_cli({"events", "--kind", "WATCHDOG_TRIP,bogus"});
  EXPECT_EQ(kind.code, 1);
  EXPECT_TRUE(contains(kind.output, "wbi events: unknown event kind 'bogus' (kinds: "))
      << kind.output;
  EXPECT_EQ(std::count(kind.output.begin(), kind.output.end(), '\n'), 1) << kind.output;
  const auto severity = wbi_cli({"events", "--severity", "loud"});
  EXPECT_EQ(severity.code, 1);
  EXPECT_TRUE(contains(severity.output, "unknown severity 'loud'")) << severity.output;
}

TEST(Cli, UnknownOptionIsNamed) {
  const auto run = wbi_cli({"topic", "list", "--bogus"});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "unknown option --bogus")) << run.output;
}

TEST(Cli, EchoOfMissingTopicTimesOut) {
  const auto run = wbi_cli({"topic", "echo", "wbi/nobody/sensors", "--timeout", "0.3"});
  EXPECT_EQ(run.code, 1);
  EXPECT_TRUE(contains(run.output, "'wbi/nobody/sensors' not found")) << run.output;
}

TEST(Cli, TopicListAndEchoSeeAnotherProcess) {
  ChildProcess talker(wbi::test::binary_dir() / "tests" / "wbi_test_talker", {"cli", "0"});
  ASSERT_TRUE(talker.wait_for_output("talker: ready", 20s)) << talker.output();

  const auto list = wbi_cli({"topic", "list", "--wait", "1.5"});
  EXPECT_EQ(list.code, 0) << list.output;
  EXPECT_TRUE(contains(list.output, "wbi/cli/sensors  [wbi::msg::SensorSample]  writers: 1"))
      << list.output;

  const auto echo = wbi_cli({"topic", "echo", "wbi/cli/sensors", "--count", "2"});
  EXPECT_EQ(echo.code, 0) << echo.output;
  EXPECT_TRUE(contains(echo.output, "robot: \"cli\"")) << echo.output;
  EXPECT_TRUE(contains(echo.output, "encoder_position: [")) << echo.output;
  std::size_t separators = 0;
  for (std::size_t at = echo.output.find("---"); at != std::string::npos;
       at = echo.output.find("---", at + 3)) {
    ++separators;
  }
  EXPECT_EQ(separators, 2u) << echo.output;

  // The talker publishes every 10 ms: `hz` measures a rate, and none above the
  // talker's 100 Hz (200: a window's edge). How close to 100 Hz it stays is the
  // machine's scheduling under load, which a test does not assert.
  const auto hz = wbi_cli({"topic", "hz", "wbi/cli/sensors", "--window", "1", "--duration", "2"});
  EXPECT_EQ(hz.code, 0) << hz.output;
  const auto at = hz.output.rfind("rate: ");
  ASSERT_NE(at, std::string::npos) << hz.output;
  const double rate = std::stod(hz.output.substr(at + 6));
  EXPECT_GT(rate, 0.0) << hz.output;
  EXPECT_LT(rate, 200.0) << hz.output;
  EXPECT_EQ(talker.stop(), 0);
}

// `wbi controller` and `wbi param` without --robot: the only robot with a
// controller host on the test's domain, named on stderr; with several, one
// line listing them; with none, one line saying so. The hosts are stubs
// (wbi_test_controller_host): real processes on the domain, no robot.
TEST(Cli, ControllerAndParamUseTheOnlyRobotOnTheDomain) {
  const char* domain_env = std::getenv("WBI_DOMAIN_ID");
  const std::string domain = "domain " + std::string(domain_env != nullptr ? domain_env : "0");
  const auto stub = wbi::test::binary_dir() / "tests" / "wbi_test_controller_host";

  const auto none = wbi_cli({"controller", "list", "--timeout", "1"});
  EXPECT_EQ(none.code, 1) << none.output;
  EXPECT_TRUE(contains(none.output,
                       "wbi controller: no controller host found on " + domain + " within 1 s"))
      << none.output;
  EXPECT_EQ(std::count(none.output.begin(), none.output.end(), '\n'), 1) << none.output;

  ChildProcess arm(stub, {"arm"});
  ASSERT_TRUE(arm.wait_for_output("stub: ready", 20s)) << arm.output();
  const std::string using_arm =
      "using robot 'arm', the only one with a controller host on " + domain + "\n";
  const auto list = wbi_cli({"controller", "list"});
  EXPECT_EQ(list.code, 0) << list.output;
  EXPECT_TRUE(contains(list.output, "wbi controller: " + using_arm)) << list.output;
  EXPECT_TRUE(contains(list.output, "* stub  [stub]  active")) << list.output;
  const auto get = wbi_cli({"param", "get", "stub", "gain"});
  EXPECT_EQ(get.code, 0) << get.output;
  EXPECT_TRUE(contains(get.output, "wbi param: " + using_arm)) << get.output;
  EXPECT_TRUE(contains(get.output, "gain = 1\n")) << get.output;

  ChildProcess others(stub, {"leg", "hand"});
  ASSERT_TRUE(others.wait_for_output("stub: ready", 20s)) << others.output();
  const auto several = wbi_cli({"param", "list", "stub"});
  EXPECT_EQ(several.code, 1) << several.output;
  EXPECT_TRUE(contains(several.output, "wbi param: 3 robots have a controller host on " + domain +
                                           " (arm, hand, leg): give --robot NAME"))
      << several.output;
  EXPECT_EQ(std::count(several.output.begin(), several.output.end(), '\n'), 1) << several.output;
  const auto named = wbi_cli({"controller", "list", "--robot", "leg"});
  EXPECT_EQ(named.code, 0) << named.output;
  EXPECT_FALSE(contains(named.output, "using robot")) << named.output;
  EXPECT_TRUE(contains(named.output, "* stub  [stub]  active")) << named.output;

  EXPECT_EQ(others.stop(), 0) << others.output();
  EXPECT_EQ(arm.stop(), 0) << arm.output();
}

}  // namespace
