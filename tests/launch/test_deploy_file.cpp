// Deploy files (the one reader, wbi/deploy/deploy_file.hpp, and what the
// launcher does with them): a good one is read completely; every mistake is
// reported with the file, the line and the field.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <wbi/launch/deploy_file.hpp>

namespace {

class DeployFileTest : public ::testing::Test {
 protected:
  std::filesystem::path write(const std::string& text) {
    const auto path = dir_ / ("deploy_" + std::to_string(count_++) + ".yaml");
    std::ofstream(path) << text;
    return path;
  }

  // The message of the error loading `text` raises.
  std::string error_of(const std::string& text) {
    const auto path = write(text);
    try {
      wbi::deploy::read_deploy_file(path);
    } catch (const std::runtime_error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path.string(), 0), 0u)
          << "error does not start with the file: " << message;
      return message.substr(path.string().size());
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return {};
  }

  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("wbi_deploy_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path dir_;
  int count_ = 0;
};

TEST_F(DeployFileTest, ReadsEveryField) {
  std::ofstream(dir_ / "qos.xml") << "<dds/>";
  const auto deploy = wbi::deploy::read_deploy_file(write(R"(
domain_id: 42
qos_file: qos.xml
environment: {A: "1"}
summary: {process: controller, match: "final max joint error"}
processes:
  - name: robot
    components:
      - {type: sim, name: sim}
    respawn: {enabled: true, delay: 0.5, max_retries: 2}
    hang_timeout: 2.5
  - name: controller
    command: [wbi_pd, --rate, "1000"]
    environment: {B: two}
    required: false
    shutdown_on_exit: true
    wait_for: {topics: [wbi/arm/state], timeout: 3}
)"));
  EXPECT_EQ(deploy.join.domain_id, 42);
  EXPECT_EQ(deploy.join.qos_file, (dir_ / "qos.xml").string());
  EXPECT_EQ(deploy.environment.at("A"), "1");
  ASSERT_EQ(deploy.processes.size(), 2u);
  const auto& robot = deploy.processes[0];
  EXPECT_TRUE(robot.hosts_components);
  EXPECT_EQ(robot.command.front(), "wbi_host");
  EXPECT_EQ(robot.command.back(), "robot");
  EXPECT_TRUE(robot.respawn.enabled);
  EXPECT_DOUBLE_EQ(robot.respawn.delay_s, 0.5);
  EXPECT_EQ(robot.respawn.max_retries, 2);
  EXPECT_TRUE(robot.required);
  EXPECT_EQ(robot.components, std::vector<std::string>{"sim"});
  EXPECT_DOUBLE_EQ(robot.hang_timeout_s, 2.5);
  EXPECT_EQ(robot.command.front(), "wbi_host");  // no host: wbi_host runs the components
  const auto& controller = deploy.processes[1];
  EXPECT_EQ(controller.command, (std::vector<std::string>{"wbi_pd", "--rate", "1000"}));
  EXPECT_EQ(controller.environment.at("B"), "two");
  EXPECT_FALSE(controller.required);
  EXPECT_TRUE(controller.shutdown_on_exit);
  EXPECT_EQ(controller.wait_for_topics, std::vector<std::string>{"wbi/arm/state"});
  EXPECT_DOUBLE_EQ(controller.wait_timeout_s, 3.0);
  EXPECT_DOUBLE_EQ(controller.hang_timeout_s, 0.0);  // not watched
  ASSERT_EQ(deploy.summaries.size(), 1u);
  EXPECT_EQ(deploy.summaries[0].process, "controller");
}

TEST_F(DeployFileTest, SeveralSummariesInFileOrder) {
  const auto deploy = wbi::deploy::read_deploy_file(write(
      "summary:\n  - {process: b, match: \"arm error\"}\n  - {process: a, match: \"com rms\"}\n"
      "processes:\n  - {name: a, command: [x]}\n  - {name: b, command: [y]}\n"));
  ASSERT_EQ(deploy.summaries.size(), 2u);
  EXPECT_EQ(deploy.summaries[0].process, "b");
  EXPECT_EQ(deploy.summaries[1].match, "com rms");
}

// host: the program that runs a components: process (a wbi_host of your own).
TEST_F(DeployFileTest, HostNamesTheProgramOfComponents) {
  const auto deploy = wbi::deploy::read_deploy_file(
      write("processes:\n  - {name: a, host: my_host, components: [{name: i, type: idle}]}\n"));
  ASSERT_EQ(deploy.processes.size(), 1u);
  EXPECT_EQ(deploy.processes[0].command.front(), "my_host");
  EXPECT_TRUE(deploy.processes[0].hosts_components);
}

TEST_F(DeployFileTest, MistakesNameFileLineAndField) {
  EXPECT_EQ(error_of("processes: []\n"), ":1: processes: expected a non-empty list of processes");
  EXPECT_EQ(error_of("processes:\n  - name: a\n    command: [x]\n    colour: red\n"),
            ":4: processes[0].colour: unknown key (known: command, components, environment, "
            "hang_timeout, host, name, plugins, required, respawn, shutdown_on_exit, wait_for)");
  EXPECT_EQ(error_of("processes:\n  - {name: a, command: [x], host: my_host}\n"),
            ":2: processes[0].host: needs 'components' (it is the program that runs them)");
  EXPECT_EQ(error_of("processes:\n  - {name: a, command: [x], hang_timeout: 2}\n"),
            ":2: processes[0].hang_timeout: needs 'components' (the heartbeats watched are its "
            "components' status)");
  EXPECT_EQ(error_of("processes:\n  - {name: a, components: [{name: i, type: idle}], "
                     "hang_timeout: 0}\n"),
            ":2: processes[0].hang_timeout: must be > 0");
  EXPECT_EQ(error_of("processes:\n  - name: a\n    command: [x]\n    respawn: {delay: soon}\n"),
            ":4: processes[0].respawn.delay: expected a number of seconds, got 'soon'");
  EXPECT_EQ(error_of("processes:\n  - name: a\n    command: [x]\n    components: [{type: sim}]\n"),
            ":2: processes[0]: needs exactly one of 'command' or 'components'");
  EXPECT_EQ(error_of("processes:\n  - {name: a, command: [x]}\n  - {name: a, command: [y]}\n"),
            ":3: processes[1].name: 'a' is used twice");
  EXPECT_EQ(error_of("summary: {process: b, match: x}\nprocesses:\n  - {name: a, command: [x]}\n"),
            ":1: summary.process: no process named 'b'");
  EXPECT_EQ(error_of("summary:\n  - {process: a, match: x}\n  - {process: c, match: y}\n"
                     "processes:\n  - {name: a, command: [x]}\n"),
            ":3: summary[1].process: no process named 'c'");
  EXPECT_EQ(error_of("domain_id: 900\nprocesses:\n  - {name: a, command: [x]}\n"),
            ":1: domain_id: must be an integer in [0, 231], got '900'");
  EXPECT_EQ(error_of("processes:\n  - {name: a, command: [x], wait_for: {timeout: -1}}\n"),
            ":2: processes[0].wait_for.timeout: must be > 0");
  const std::string syntax = error_of("processes:\n  - name: [unclosed\n");
  EXPECT_NE(syntax.find("YAML syntax error"), std::string::npos) << syntax;
  EXPECT_EQ(syntax.rfind(":3", 0), 0u) << syntax;
}

TEST_F(DeployFileTest, MissingFileIsNamed) {
  try {
    wbi::deploy::read_deploy_file(dir_ / "absent.yaml");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("absent.yaml: cannot read the deploy file"),
              std::string::npos)
        << e.what();
  }
}

// `wbi launch --one-process`: one process hosting every component in file order,
// ending the launch when it ends; the summaries read from it.
TEST_F(DeployFileTest, OneProcessHostsEveryComponentInFileOrder) {
  const auto deploy = wbi::launch::in_one_process(wbi::deploy::read_deploy_file(write(R"(
summary: {process: controller, match: "final max joint error"}
processes:
  - name: robot
    components: [{type: sim_robot, name: sim}]
    environment: {A: "1"}
  - name: estimator
    wait_for: {topics: [wbi/arm/sensors], timeout: 30}
    respawn: {enabled: true}
    hang_timeout: 3
    components: [{type: estimator, name: estimator}]
  - name: controller
    environment: {A: "1", B: "2"}
    components: [{type: pd_gravity, name: pd}, {type: com_sinusoid, name: reference}]
)")));
  ASSERT_EQ(deploy.processes.size(), 1u);
  const auto& one = deploy.processes[0];
  EXPECT_EQ(one.name, "all");
  EXPECT_EQ(one.components, (std::vector<std::string>{"sim", "estimator", "pd", "reference"}));
  ASSERT_EQ(one.command.size(), 4u);
  EXPECT_EQ(one.command[0], "wbi_host");
  EXPECT_EQ(one.command[2], "--process");
  EXPECT_EQ(one.command[3], "robot,estimator,controller");
  EXPECT_TRUE(one.wait_for_topics.empty());
  EXPECT_FALSE(one.respawn.enabled);
  EXPECT_TRUE(one.shutdown_on_exit);
  EXPECT_DOUBLE_EQ(one.hang_timeout_s, 3.0);
  EXPECT_EQ(one.environment, (std::map<std::string, std::string>{{"A", "1"}, {"B", "2"}}));
  ASSERT_EQ(deploy.summaries.size(), 1u);
  EXPECT_EQ(deploy.summaries[0].process, "all");
}

TEST_F(DeployFileTest, OneProcessNamesWhatCannotShareAProcess) {
  const auto error_in_one_process = [&](const std::string& text) -> std::string {
    const auto path = write(text);
    try {
      wbi::launch::in_one_process(wbi::deploy::read_deploy_file(path));
    } catch (const std::runtime_error& e) {
      return std::string(e.what()).substr(path.string().size());
    }
    return "(no error)";
  };
  EXPECT_EQ(error_in_one_process(R"(
processes:
  - {name: robot, components: [{type: sim_robot, name: sim}]}
  - {name: viewer, command: [wbi-plot]}
)"),
            ": --one-process: process 'viewer' runs a command, not components: only components "
            "can share a process");
  EXPECT_EQ(error_in_one_process(R"(
processes:
  - {name: robot, components: [{type: sim_robot, name: sim}], environment: {A: "1"}}
  - {name: controller, components: [{type: idle, name: c}], environment: {A: "2"}}
)"),
            ": --one-process: process 'controller' sets A=2, an earlier one A=1");
  EXPECT_EQ(error_in_one_process(R"(
processes:
  - {name: robot, components: [{type: sim_robot, name: sim}]}
  - {name: controller, host: my_host, components: [{type: idle, name: c}]}
)"),
            ": --one-process: processes 'robot' and 'controller' name different host programs "
            "(wbi_host, my_host)");
}

// `wbi launch FILE --process A,B`: one host's part of a deployment, in file
// order whatever the order named, with only its summaries.
TEST_F(DeployFileTest, OnlyProcessesKeepsTheNamedOnesInFileOrder) {
  const auto path = write(R"(
summary:
  - {process: robot, match: "ground truth"}
  - {process: controller, match: "final max joint error"}
processes:
  - {name: robot, components: [{type: sim_robot, name: sim}]}
  - name: estimator
    wait_for: {topics: [wbi/arm/sensors], timeout: 30}
    components: [{type: estimator, name: estimator}]
  - {name: controller, components: [{type: pd_gravity, name: pd}]}
)");
  const auto part =
      wbi::launch::only_processes(wbi::deploy::read_deploy_file(path), {"controller", "estimator"});
  ASSERT_EQ(part.processes.size(), 2u);
  EXPECT_EQ(part.processes[0].name, "estimator");
  EXPECT_EQ(part.processes[0].wait_for_topics, (std::vector<std::string>{"wbi/arm/sensors"}));
  EXPECT_EQ(part.processes[1].name, "controller");
  ASSERT_EQ(part.summaries.size(), 1u);
  EXPECT_EQ(part.summaries[0].process, "controller");

  const auto error_of_only = [&](const std::vector<std::string>& names) -> std::string {
    try {
      wbi::launch::only_processes(wbi::deploy::read_deploy_file(path), names);
    } catch (const std::runtime_error& e) {
      return std::string(e.what()).substr(path.string().size());
    }
    return "(no error)";
  };
  EXPECT_EQ(error_of_only({"robot", "planner"}),
            ": --process: no process named 'planner' (the file has: robot, estimator, controller)");
  EXPECT_EQ(error_of_only({"robot", "robot"}), ": --process: process 'robot' named twice");
  EXPECT_EQ(error_of_only({}), ": --process: no process named");
}

}  // namespace
