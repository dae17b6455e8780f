// The pd_gravity component: the model source is configuration only
// (`model: local | remote`), a wrong value is named, and with the remote model
// it runs against the robot and the model service and stamps its commands
// with the sensor sample they answer.
#include <gtest/gtest.h>

#include <wbi/catalog.hpp>
#include <wbi/runtime/clock.hpp>
#include <wbi/runtime/plugins.hpp>
#include <wbi/runtime/registry.hpp>
#include <wbi/runtime/runner.hpp>

#include "remote_model_peer.hpp"

namespace {

using namespace wbi::test;

struct Host {
  wbi::dds::Participant participant{"controller"};
  wbi::runtime::SystemClock clock;
  wbi::Catalog catalog;  // the built-in plugin's types, as wbi_host has them
  std::unique_ptr<wbi::runtime::ComponentRunner> runner;

  Host() {
    wbi::runtime::load_plugins(catalog, {});
    const auto& registry = catalog.registry<wbi::runtime::Registry>();
    wbi::runtime::RunnerOptions options;
    options.rate_hz = 200.0;
    runner = std::make_unique<wbi::runtime::ComponentRunner>(
        registry.create("pd_gravity"),
        wbi::runtime::ComponentContext{"pd", "pd_gravity", &participant, &clock}, options);
  }
};

std::string parameters(const std::string& robot, const std::string& model_lines) {
  return "robot: " + robot + "\n" + model_lines +
         "joints: [joint_1, joint_2]\ntarget: [0.1, 0.2]\nmax_age_s: 0.5\n"
         "init_timeout_s: 20\nprogress_period_s: 0\n"
         "claim: none\n";  // ArmPeer answers no claims
}

TEST(PdGravityComponent, AnUnknownModelSourceIsNamed) {
  Host host;
  try {
    host.runner->configure(
        wbi::runtime::Parameters::from_string(parameters("arm_none", "model: cloud\n")));
    FAIL() << "model: cloud accepted";
  } catch (const wbi::runtime::TransitionError& e) {
    EXPECT_NE(std::string(e.what()).find("model is 'cloud'; expected local or remote"),
              std::string::npos)
        << e.what();
  }
}

TEST(PdGravityComponent, RunsWithTheRemoteModelAndStampsItsCommands) {
  ArmPeer peer("arm_pd_remote");
  const auto service = start_model_service("arm_pd_remote");
  Host host;
  host.runner->configure(
      wbi::runtime::Parameters::from_string(parameters("arm_pd_remote", "model: remote\n")));
  host.runner->activate();
  wbi::dds::Received<wbi::msg::ActuatorCommand> command;
  ASSERT_TRUE(peer.commands().wait_newer(command, 5, 10s));
  const auto& c = command.sample;
  ASSERT_EQ(c.references().size(), 2u);
  EXPECT_EQ(c.modes()[0], wbi::msg::ControlMode::TORQUE);
  EXPECT_NE(c.references()[1], 0.0);
  // The peer stamps its samples seq · 5 ms: the command names one of them.
  EXPECT_GT(c.source_stamp_ns(), 0);
  EXPECT_EQ(c.source_stamp_ns(), static_cast<std::int64_t>(c.tick()) * 5'000'000);
  host.runner->shutdown();
}

}  // namespace
