// A deploy file has one reader (wbi/deploy/deploy_file.hpp): the launcher
// (read_deploy_file), wbi_host (load_process_host) and the wbi tools
// (read_join_options, `--deploy FILE`) report a mistake with the same
// message, checked in one place and given once, with the file and the line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>

#include <wbi/deploy/deploy_file.hpp>
#include <wbi/deploy/placement.hpp>
#include <wbi/deploy/process_host.hpp>

namespace {

class OneReader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        std::filesystem::temp_directory_path() / ("wbi-one-reader-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
    file_ = (dir_ / "deploy.yaml").string();
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // The message each reader of the file gives, or "(no error)".
  static std::string error_of(const std::function<void()>& read) {
    try {
      read();
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "(no error)";
  }

  // What the launcher, wbi_host and a tool say of `text`: one message, or a
  // list of the three that differ.
  std::string errors_of(const std::string& text) {
    std::ofstream(file_) << text;
    const std::string launcher = error_of([&] { wbi::deploy::read_deploy_file(file_); });
    const std::string host = error_of([&] { wbi::deploy::load_process_host(file_, "robot"); });
    const std::string tool = error_of([&] {
      wbi::dds::ParticipantOptions options;
      wbi::deploy::read_join_options(file_, "observer", options);
    });
    if (launcher == host && host == tool) {
      return launcher;
    }
    return "launcher: " + launcher + "\nwbi_host: " + host + "\ntool: " + tool;
  }

  std::filesystem::path dir_;
  std::string file_;
};

TEST_F(OneReader, TheDomainIdIsCheckedOnceWithTheFileAndTheLine) {
  const std::string message = errors_of(
      "processes:\n  - {name: robot, components: [{name: i, type: idle}]}\n"
      "domain_id: 900\n");
  EXPECT_EQ(message, file_ + ":3: domain_id: must be an integer in [0, 231], got '900'");
  // Said once: no reader wraps it in another's words.
  EXPECT_EQ(message.find("domain_id", message.find("domain_id") + 1), std::string::npos);
  EXPECT_EQ(errors_of("domain_id: seven\nprocesses: [{name: robot, command: [x]}]\n"),
            file_ + ":1: domain_id: must be an integer in [0, 231], got 'seven'");
}

TEST_F(OneReader, EveryCheckIsEveryReaders) {
  EXPECT_EQ(errors_of("qos_file: none.xml\nprocesses: [{name: robot, command: [x]}]\n"),
            file_ + ":1: qos_file: no such file: " + (dir_ / "none.xml").string());
  EXPECT_EQ(
      errors_of("network: {discovery: broadcast}\nprocesses: [{name: robot, command: [x]}]\n"),
      file_ +
          ":1: network.discovery: must be localhost, multicast, peers or server, got "
          "'broadcast'");
  EXPECT_EQ(errors_of("processes:\n  - {name: robot, command: [x], respawn: {delay: -1}}\n"),
            file_ + ":2: processes[0].respawn.delay: must be >= 0");
  EXPECT_EQ(errors_of("colour: red\nprocesses: [{name: robot, command: [x]}]\n"),
            file_ +
                ":1: colour: unknown key (known: domain_id, environment, network, plugins, "
                "processes, qos_file, security, summary)");
  EXPECT_EQ(errors_of("processes: [{name: robot, command: [x]}\n"),
            file_ + ":2: YAML syntax error: end of sequence flow not found");
}

TEST_F(OneReader, AGoodFileJoinsTheSameForEveryReader) {
  std::ofstream(dir_ / "qos.xml") << "<dds/>";
  std::ofstream(file_) << "domain_id: 12\nqos_file: qos.xml\n"
                          "security: {directory: keys}\n"
                          "processes: [{name: robot, components: [{name: i, type: idle}]}]\n";
  wbi::dds::ParticipantOptions tool;
  wbi::deploy::read_join_options(file_, "observer", tool);
  wbi::dds::ParticipantOptions host;
  const auto process = wbi::deploy::load_process_host(file_, "robot");
  wbi::deploy::apply_join_keys(process.join, "robot", host);
  for (const auto* options : {&tool, &host}) {
    EXPECT_EQ(options->domain_id, 12);
    EXPECT_EQ(std::filesystem::path(options->qos_file), dir_ / "qos.xml");
    EXPECT_EQ(std::filesystem::path(options->security.directory), dir_ / "keys");
  }
  EXPECT_EQ(tool.security.identity, "observer");
  EXPECT_EQ(host.security.identity, "robot");
}

}  // namespace
