// One process of a deploy file as a host document (wbi/deploy/process_host.hpp):
// its components and plugins, marks kept for error lines, and errors naming
// the file for an unknown process or one without components. The deploy's
// join keys stay with the deploy file (apply_join_keys), checked once.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include <wbi/deploy/process_host.hpp>

namespace {

const char* kDeploy = R"(domain_id: 7
plugins: [lab]
network: {discovery: multicast}
processes:
  - name: robot
    plugins: [robots]
    components:
      - {name: sim, type: sim_robot}
  - name: viewer
    command: [wbi-plot]
)";

wbi::deploy::DeployFile deploy_of(const std::string& yaml) {
  return wbi::deploy::read_deploy_file(YAML::Load(yaml), "deploy.yaml");
}

std::string error_of(const std::string& process) {
  try {
    wbi::deploy::process_host_document(deploy_of(kDeploy), {process});
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(ProcessHost, TakesTheProcessComponentsAndPlugins) {
  const YAML::Node host = wbi::deploy::process_host_document(deploy_of(kDeploy), {"robot"});
  ASSERT_TRUE(host["components"].IsSequence());
  ASSERT_EQ(host["components"].size(), 1U);
  EXPECT_EQ(host["components"][0]["type"].as<std::string>(), "sim_robot");
  EXPECT_EQ(host["plugins"].as<std::vector<std::string>>(),
            (std::vector<std::string>{"lab", "robots"}));
  // Errors about a component still name the deploy file's line (0-based mark).
  EXPECT_EQ(host["components"][0].Mark().line, 7);
  // The join keys were read and checked by the deploy reader: not again by the runtime.
  for (const char* key : {"domain_id", "qos_file", "network", "security", "processes"}) {
    EXPECT_FALSE(host[key]) << key;
  }
}

TEST(ProcessHost, TheJoinKeysComeFromTheDeployFile) {
  wbi::dds::ParticipantOptions options;
  wbi::deploy::apply_join_keys(deploy_of(kDeploy).join, "robot", options);
  EXPECT_EQ(options.domain_id, 7);
  EXPECT_EQ(options.discovery, wbi::dds::Discovery::multicast);
  EXPECT_EQ(options.security.identity, "robot");  // recorded for a directory given later
  EXPECT_FALSE(options.security.enabled());
}

TEST(ProcessHost, AnUnknownProcessOrOneWithoutComponentsIsNamed) {
  EXPECT_EQ(error_of("estimator"), "deploy.yaml: no process named 'estimator' in the deploy file");
  EXPECT_EQ(error_of("viewer"), "deploy.yaml:9: process 'viewer' has no 'components' to host");
}

// `wbi_host DEPLOY --process a,b`: the components of both, in the order named.
TEST(ProcessHost, SeveralProcessesGiveTheirComponentsInTheOrderNamed) {
  const auto deploy = deploy_of(R"(processes:
  - name: robot
    components: [{name: sim, type: sim_robot}]
  - name: controller
    components: [{name: pd, type: pd_gravity}, {name: hold, type: idle}]
)");
  const YAML::Node host = wbi::deploy::process_host_document(deploy, {"controller", "robot"});
  ASSERT_EQ(host["components"].size(), 3U);
  EXPECT_EQ(host["components"][0]["name"].as<std::string>(), "pd");
  EXPECT_EQ(host["components"][1]["name"].as<std::string>(), "hold");
  EXPECT_EQ(host["components"][2]["name"].as<std::string>(), "sim");
  EXPECT_FALSE(host["plugins"]);
  try {
    wbi::deploy::process_host_document(deploy, {"robot", "viewer"});
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
