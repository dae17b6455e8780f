// The network and security blocks of deploy files (wbi/deploy/placement.hpp):
// each discovery mode, the environment overrides, and errors that name the
// file, the line and the field.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

#include <wbi/deploy/placement.hpp>

namespace {

using wbi::dds::Discovery;
using wbi::dds::ParticipantOptions;

ParticipantOptions read(const std::string& yaml, const std::string& identity = "controller") {
  ParticipantOptions options;
  wbi::deploy::read_placement(YAML::Load(yaml), "deploy.yaml", identity, options);
  return options;
}

std::string error_of(const std::string& yaml) {
  try {
    read(yaml);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(Placement, WithoutBlocksTheParticipantStaysOnThisHostWithoutSecurity) {
  const auto options = read("processes: []");
  EXPECT_EQ(options.discovery, Discovery::localhost);
  EXPECT_TRUE(options.network.peers.empty());
  EXPECT_FALSE(options.security.enabled());
}

TEST(Placement, EachDiscoveryMode) {
  auto options = read("network: {interfaces: [10.0.0.1, 10.0.0.2]}");
  EXPECT_EQ(options.discovery, Discovery::multicast);  // a network block means other hosts
  EXPECT_EQ(options.network.interfaces, (std::vector<std::string>{"10.0.0.1", "10.0.0.2"}));
  options = read("network: {discovery: peers, peers: [10.0.0.1, '10.0.0.2:7412']}");
  EXPECT_EQ(options.discovery, Discovery::peers);
  EXPECT_EQ(options.network.peers, (std::vector<std::string>{"10.0.0.1", "10.0.0.2:7412"}));
  options = read("network: {discovery: server, server: '10.0.0.1:11811'}");
  EXPECT_EQ(options.discovery, Discovery::server);
  EXPECT_EQ(options.network.discovery_server, "10.0.0.1:11811");
  EXPECT_EQ(read("network: {discovery: localhost}").discovery, Discovery::localhost);
}

TEST(Placement, MistakesNameTheLineAndTheField) {
  EXPECT_EQ(error_of("a: 1\nnetwork: {discovery: broadcast}"),
            "deploy.yaml:2: network.discovery: must be localhost, multicast, peers or server, got "
            "'broadcast'");
  EXPECT_EQ(
      error_of("network:\n  peer: [10.0.0.1]"),
      "deploy.yaml:2: network.peer: unknown key (known: discovery, interfaces, peers, server)");
  EXPECT_EQ(error_of("network: {peers: 10.0.0.1}"),
            "deploy.yaml:1: network.peers: expected a list of addresses");
  EXPECT_EQ(error_of("security: {identity: robot}"), "deploy.yaml:1: security.directory: missing");
}

TEST(Placement, SecurityDirectoryIsRelativeToTheFileAndIdentityDefaultsToTheProcess) {
  const auto dir = std::filesystem::temp_directory_path() / "wbi-placement-test" / "keys";
  std::filesystem::create_directories(dir);
  ParticipantOptions options;
  wbi::deploy::read_placement(YAML::Load("security: {directory: keys}"),
                              (dir.parent_path() / "deploy.yaml").string(), "estimator", options);
  EXPECT_EQ(std::filesystem::path(options.security.directory), dir.parent_path() / "keys");
  EXPECT_EQ(options.security.identity, "estimator");
  wbi::deploy::read_placement(YAML::Load("security: {directory: keys, identity: observer}"),
                              (dir.parent_path() / "deploy.yaml").string(), "estimator", options);
  EXPECT_EQ(options.security.identity, "observer");
  std::filesystem::remove_all(dir.parent_path());
  // A directory that does not exist is the participant's to name: the
  // environment or a flag may still replace it.
  options = read("security: {directory: /no/such/dir}");
  EXPECT_EQ(options.security.directory, "/no/such/dir");
}

TEST(Placement, TheFileReaderReadsTheFileOnly) {
  // The environment is the next layer (dds::apply_environment), not the reader's.
  setenv("WBI_DDS_DISCOVERY", "peers", 1);
  const auto options = read("network: {discovery: multicast, peers: [10.0.0.9]}");
  unsetenv("WBI_DDS_DISCOVERY");
  EXPECT_EQ(options.discovery, Discovery::multicast);
  EXPECT_EQ(options.network.peers, (std::vector<std::string>{"10.0.0.9"}));
  // Without a security block the identity is still recorded, for a directory given later.
  EXPECT_EQ(options.security.identity, "controller");
  EXPECT_FALSE(options.security.enabled());
}

}  // namespace
