// One process of a deploy file as a host document (wbi/deploy/process_host.hpp):
// its components and the deploy's join keys, marks kept for error lines, and
// errors naming the file for an unknown process or one without components.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include <wbi/deploy/process_host.hpp>

namespace {

const char* kDeploy = R"(domain_id: 7
qos_file: qos_profiles.xml
network: {discovery: multicast}
processes:
  - name: robot
    command: wbi_host
    components:
      - {name: sim, type: sim_robot}
  - name: viewer
    command: wbi-plot
)";

std::string error_of(const std::string& process) {
  try {
    wbi::deploy::process_host_document(YAML::Load(kDeploy), "deploy.yaml", process);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(ProcessHost, TakesTheProcessComponentsAndTheDeploysJoinKeys) {
  const YAML::Node host =
      wbi::deploy::process_host_document(YAML::Load(kDeploy), "deploy.yaml", "robot");
  ASSERT_TRUE(host["components"].IsSequence());
  ASSERT_EQ(host["components"].size(), 1U);
  EXPECT_EQ(host["components"][0]["type"].as<std::string>(), "sim_robot");
  EXPECT_EQ(host["domain_id"].as<int>(), 7);
  EXPECT_EQ(host["qos_file"].as<std::string>(), "qos_profiles.xml");
  EXPECT_EQ(host["network"]["discovery"].as<std::string>(), "multicast");
  EXPECT_FALSE(host["security"]);
  EXPECT_FALSE(host["processes"]) << "nothing but the host keys";
  // Errors about a component still name the deploy file's line (0-based mark).
  EXPECT_EQ(host["components"][0].Mark().line, 7);
}

TEST(ProcessHost, AnUnknownProcessOrOneWithoutComponentsIsNamed) {
  EXPECT_EQ(error_of("estimator"), "deploy.yaml: no process named 'estimator' in the deploy file");
  EXPECT_EQ(error_of("viewer"), "deploy.yaml:9: process 'viewer' has no 'components' to host");
}

// `wbi_host DEPLOY --process a,b`: the components of both, in the order named.
TEST(ProcessHost, SeveralProcessesGiveTheirComponentsInTheOrderNamed) {
  const YAML::Node deploy = YAML::Load(R"(processes:
  - name: robot
    components: [{name: sim, type: sim_robot}]
  - name: controller
    components: [{name: pd, type: pd_gravity}, {name: hold, type: idle}]
)");
  const YAML::Node host = wbi::deploy::process_host_document(
      deploy, "deploy.yaml", std::vector<std::string>{"controller", "robot"});
  ASSERT_EQ(host["components"].size(), 3U);
  EXPECT_EQ(host["components"][0]["name"].as<std::string>(), "pd");
  EXPECT_EQ(host["components"][1]["name"].as<std::string>(), "hold");
  EXPECT_EQ(host["components"][2]["name"].as<std::string>(), "sim");
  try {
    wbi::deploy::process_host_document(deploy, "deploy.yaml",
                                       std::vector<std::string>{"robot", "viewer"});
    FAIL() << "no error";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "deploy.yaml: no process named 'viewer' in the deploy file");
  }
}

TEST(ProcessHost, AFileThatCannotBeReadIsNamed) {
  try {
    wbi::deploy::load_process_host("/nonexistent/deploy.yaml", "robot");
    FAIL() << "no error";
  } catch (const std::runtime_error& error) {
    EXPECT_STREQ(error.what(), "/nonexistent/deploy.yaml: cannot read the deploy file");
  }
}

}  // namespace
