// The join options' precedence (dds/README.md, "Joining a deployment"):
// defaults < deploy file < WBI_* environment < command-line flags, through the
// code every `wbi` DDS verb uses (cli/src/join_options.hpp). No DDS traffic.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "join_options.hpp"

namespace {

using wbi::dds::Discovery;
using wbi::dds::ParticipantOptions;
using Strings = std::vector<std::string>;

const char* const kVariables[] = {"WBI_DOMAIN_ID",
                                  "WBI_QOS_FILE",
                                  "WBI_DDS_DISCOVERY",
                                  "WBI_DDS_PEERS",
                                  "WBI_DDS_INTERFACES",
                                  "WBI_DDS_DISCOVERY_SERVER",
                                  "WBI_DDS_SECURITY_DIRECTORY",
                                  "WBI_DDS_SECURITY_IDENTITY"};

// Clears the join variables for the test, restores them after (ctest sets WBI_DOMAIN_ID).
class JoinOptions : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : kVariables) {
      if (const char* value = std::getenv(name)) {
        saved_[name] = value;
      }
      unsetenv(name);
    }
    dir_ =
        std::filesystem::temp_directory_path() / ("wbi-join-options-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_ / "keys");
    std::filesystem::create_directories(dir_ / "other_keys");
    deploy_ = (dir_ / "deploy.yaml").string();
    std::ofstream(deploy_) << "domain_id: 5\n"
                              "network: {discovery: multicast, interfaces: [10.0.0.1]}\n"
                              "security: {directory: keys, identity: controller}\n"
                              "processes: [{name: robot, command: [x]}]\n";
  }
  void TearDown() override {
    for (const char* name : kVariables) {
      unsetenv(name);
    }
    for (const auto& [name, value] : saved_) {
      setenv(name.c_str(), value.c_str(), 1);
    }
    std::filesystem::remove_all(dir_);
  }

  // What `wbi topic list ARGS...` would join with.
  static ParticipantOptions join(Strings args, const std::string& identity = "observer") {
    wbi::cli::Options options("test", "test");
    wbi::cli::add_join_options(options);
    EXPECT_TRUE(options.parse(args));
    return wbi::cli::join_options(options, "test", identity);
  }

  std::map<std::string, std::string> saved_;
  std::filesystem::path dir_;
  std::string deploy_;
};

TEST_F(JoinOptions, DefaultsStayOnThisHostWithoutSecurity) {
  const auto options = join({});
  EXPECT_EQ(options.domain_id, 0);
  EXPECT_EQ(options.discovery, Discovery::localhost);
  EXPECT_TRUE(options.network.peers.empty());
  EXPECT_TRUE(options.network.interfaces.empty());
  EXPECT_FALSE(options.security.enabled());
}

TEST_F(JoinOptions, TheDeployFileBeatsTheDefaultsAndTheToolKeepsItsOwnIdentity) {
  const auto options = join({"--deploy", deploy_});
  EXPECT_EQ(options.domain_id, 5);
  EXPECT_EQ(options.discovery, Discovery::multicast);
  EXPECT_EQ(options.network.interfaces, Strings{"10.0.0.1"});
  EXPECT_EQ(std::filesystem::path(options.security.directory), dir_ / "keys");
  // The file's identity is its processes'; the tool joins as the observer.
  EXPECT_EQ(options.security.identity, "observer");
}

TEST_F(JoinOptions, TheEnvironmentBeatsTheFile) {
  setenv("WBI_DOMAIN_ID", "6", 1);
  setenv("WBI_DDS_INTERFACES", "10.0.0.2", 1);
  setenv("WBI_DDS_PEERS", "10.0.0.3,10.0.0.4:7412", 1);
  setenv("WBI_DDS_SECURITY_DIRECTORY", (dir_ / "other_keys").c_str(), 1);
  setenv("WBI_DDS_SECURITY_IDENTITY", "recorder", 1);
  const auto options = join({"--deploy", deploy_});
  EXPECT_EQ(options.domain_id, 6);
  EXPECT_EQ(options.discovery, Discovery::peers);  // peers given: peers mode
  EXPECT_EQ(options.network.interfaces, Strings{"10.0.0.2"});
  EXPECT_EQ(options.network.peers, (Strings{"10.0.0.3", "10.0.0.4:7412"}));
  EXPECT_EQ(std::filesystem::path(options.security.directory), dir_ / "other_keys");
  EXPECT_EQ(options.security.identity, "recorder");
}

TEST_F(JoinOptions, FlagsBeatTheEnvironment) {
  setenv("WBI_DOMAIN_ID", "6", 1);
  setenv("WBI_DDS_DISCOVERY", "peers", 1);
  setenv("WBI_DDS_PEERS", "10.0.0.3", 1);
  setenv("WBI_DDS_INTERFACES", "10.0.0.2", 1);
  setenv("WBI_DDS_SECURITY_IDENTITY", "recorder", 1);
  const auto options = join({"--deploy", deploy_, "--domain", "7", "--discovery-server",
                             "10.0.0.9:11811", "--interfaces", "10.0.0.5,10.0.0.6", "--security",
                             (dir_ / "other_keys").string(), "--identity", "controller"});
  EXPECT_EQ(options.domain_id, 7);
  EXPECT_EQ(options.discovery, Discovery::server);  // a server given: server mode
  EXPECT_EQ(options.network.discovery_server, "10.0.0.9:11811");
  EXPECT_EQ(options.network.peers, Strings{"10.0.0.3"});  // not given as a flag: the environment's
  EXPECT_EQ(options.network.interfaces, (Strings{"10.0.0.5", "10.0.0.6"}));
  EXPECT_EQ(std::filesystem::path(options.security.directory), dir_ / "other_keys");
  EXPECT_EQ(options.security.identity, "controller");
  // An explicit mode beats the one the addresses imply.
  EXPECT_EQ(join({"--peers", "10.0.0.3", "--discovery", "multicast"}).discovery,
            Discovery::multicast);
}

TEST_F(JoinOptions, MistakesNameTheFlagTheVariableOrTheFileLine) {
  auto error_of = [&](Strings args, const std::string& identity = "observer") -> std::string {
    try {
      join(std::move(args), identity);
    } catch (const std::exception& error) {
      return error.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(error_of({"--domain", "300"}), "--domain: must be an integer in [0, 231], got '300'");
  EXPECT_EQ(error_of({"--discovery", "broadcast"}),
            "--discovery: must be localhost, multicast, peers or server, got 'broadcast'");
  setenv("WBI_DOMAIN_ID", "x", 1);
  EXPECT_EQ(error_of({}), "WBI_DOMAIN_ID: must be an integer in [0, 231], got 'x'");
  unsetenv("WBI_DOMAIN_ID");
  std::ofstream(deploy_) << "network: {discovery: broadcast}\n";
  EXPECT_EQ(error_of({"--deploy", deploy_}),
            "--deploy " + deploy_ +
                ":1: network.discovery: must be localhost, multicast, peers or server, got "
                "'broadcast'");
  EXPECT_NE(error_of({"--deploy", (dir_ / "none.yaml").string()}).find("cannot read"),
            std::string::npos);
  // A verb that publishes has no default identity: it asks for one.
  EXPECT_NE(error_of({"--security", (dir_ / "keys").string()}, "").find("give --identity NAME"),
            std::string::npos);
}

}  // namespace
