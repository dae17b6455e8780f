// The model service: the evaluator's replies and errors, the component's
// lifecycle over DDS, its latched description, and bad parameters.
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <string>

#include <wbi/dds/client.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/model/urdf.hpp>
#include <wbi/model_service/component.hpp>
#include <wbi/runtime/runner.hpp>

#include "model_fixture.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::msg::ModelReply;
using wbi::msg::ModelRequest;

struct EvaluatorTest : ::testing::Test {
  wbi::model::Model model =
      wbi::model::load_urdf_file(wbi::test::project_model("humanoid.urdf").string());
  wbi::model::Data data{model};
  wbi::model_service::Evaluator evaluator{model, "humanoid"};
  std::mt19937 rng{7};
  ModelRequest request;
  ModelReply reply;
};

TEST_F(EvaluatorTest, EveryOperationMatchesTheLibrary) {
  for (int round = 0; round < 20; ++round) {
    wbi::test::random_model_request(model, "humanoid", rng, wbi::test::every_model_operation(),
                                    request);
    evaluator.evaluate(request, reply);
    ASSERT_EQ(wbi::test::model_mismatch(model, data, request, reply), "") << "round " << round;
    EXPECT_GT(reply.compute_ns(), 0);
  }
  EXPECT_EQ(reply.results()[0].rows(), static_cast<std::uint32_t>(model.nv));
  EXPECT_EQ(reply.results()[4].rows(), 6u);
}

TEST_F(EvaluatorTest, InverseAndForwardDynamicsAreConsistent) {
  wbi::test::random_model_request(model, "humanoid", rng, {wbi::msg::INVERSE_DYNAMICS}, request);
  request.nu_dot().assign(static_cast<std::size_t>(model.nv), 0.0);
  evaluator.evaluate(request, reply);
  ASSERT_STREQ(reply.error().c_str(), "");
  // With ν̇ = 0, inverse dynamics is h.
  ModelRequest h_request = request;
  h_request.operations()[0].operation(wbi::msg::BIAS_FORCES);
  ModelReply h_reply;
  evaluator.evaluate(h_request, h_reply);
  ASSERT_EQ(reply.results()[0].data().size(), h_reply.results()[0].data().size());
  for (std::size_t i = 0; i < reply.results()[0].data().size(); ++i) {
    EXPECT_NEAR(reply.results()[0].data()[i], h_reply.results()[0].data()[i], 1e-9);
  }
  // Forward dynamics with τ = 0 answers nv accelerations.
  request.operations()[0].operation(wbi::msg::FORWARD_DYNAMICS);
  request.tau().assign(static_cast<std::size_t>(model.n_joints), 0.0);
  evaluator.evaluate(request, reply);
  ASSERT_STREQ(reply.error().c_str(), "");
  EXPECT_EQ(reply.results()[0].rows(), static_cast<std::uint32_t>(model.nv));
}

TEST_F(EvaluatorTest, BadRequestsGetErrorRepliesNamingTheProblem) {
  const auto error_of = [&](const std::function<void(ModelRequest&)>& spoil) {
    wbi::test::random_model_request(model, "humanoid", rng, {wbi::msg::JACOBIAN}, request);
    spoil(request);
    evaluator.evaluate(request, reply);
    EXPECT_TRUE(reply.results().empty());
    return std::string(reply.error().c_str());
  };
  EXPECT_EQ(error_of([](ModelRequest& r) { r.robot("icub"); }),
            "unknown robot 'icub': this service serves 'humanoid'");
  EXPECT_EQ(error_of([](ModelRequest& r) { r.operations()[0].frame("nose"); }),
            "JACOBIAN: unknown frame 'nose' in robot 'humanoid'");
  EXPECT_EQ(error_of([](ModelRequest& r) { r.state().q().resize(3); }),
            "state.q has 3 values, robot 'humanoid' needs " + std::to_string(model.n_joints));
  EXPECT_NE(
      error_of([](ModelRequest& r) { r.state().dq().resize(2); }).find("state.dq has 2 values"),
      std::string::npos);
  EXPECT_NE(error_of([](ModelRequest& r) {
              r.state().base_pose().orientation().w(0.0);
            }).find("must be a unit quaternion"),
            std::string::npos);
  EXPECT_NE(error_of([](ModelRequest& r) {
              r.operations()[0].operation(wbi::msg::INVERSE_DYNAMICS);
            }).find("INVERSE_DYNAMICS: nu_dot has 0 values"),
            std::string::npos);
  EXPECT_NE(error_of([](ModelRequest& r) {
              r.operations()[0].operation(wbi::msg::FORWARD_DYNAMICS);
            }).find("FORWARD_DYNAMICS: tau has 0 values"),
            std::string::npos);
  // A good request afterwards is answered normally.
  wbi::test::random_model_request(model, "humanoid", rng, {wbi::msg::COM}, request);
  evaluator.evaluate(request, reply);
  EXPECT_EQ(wbi::test::model_mismatch(model, data, request, reply), "");
}

TEST_F(EvaluatorTest, FixedBaseArm) {
  wbi::model::LoadOptions options;
  options.fixed_base = true;
  const auto arm =
      wbi::model::load_urdf_file(wbi::test::project_model("arm7.urdf").string(), options);
  wbi::model::Data arm_data(arm);
  wbi::model_service::Evaluator arm_evaluator(arm, "arm");
  for (int round = 0; round < 5; ++round) {
    wbi::test::random_model_request(
        arm, "arm", rng, {wbi::msg::GRAVITY_FORCES, wbi::msg::MASS_MATRIX, wbi::msg::JACOBIAN},
        request);
    request.state().base_pose().orientation().w(0.0);  // ignored for a fixed base
    arm_evaluator.evaluate(request, reply);
    ASSERT_EQ(wbi::test::model_mismatch(arm, arm_data, request, reply), "");
    EXPECT_EQ(reply.results()[1].rows(), static_cast<std::uint32_t>(arm.nv));
  }
}

// The component in a runner, a client in another participant.
struct ComponentTest : ::testing::Test {
  wbi::dds::Participant service_side{"service"};
  wbi::dds::Participant client_side{"client"};
  wbi::runtime::SystemClock clock;
  std::unique_ptr<wbi::runtime::ComponentRunner> runner;

  void make() {
    runner = std::make_unique<wbi::runtime::ComponentRunner>(
        std::make_unique<wbi::model_service::ModelServiceComponent>(),
        wbi::runtime::ComponentContext{"model", "model_service", &service_side, &clock});
  }
};

TEST_F(ComponentTest, ServesOnlyWhileActive) {
  make();
  runner->configure(wbi::runtime::Parameters::from_string(
      "urdf: " + wbi::test::project_model("humanoid.urdf").string() + "\nrobot: hum"));
  const auto model = wbi::model::load_urdf_file(wbi::test::project_model("humanoid.urdf").string());
  wbi::model::Data data(model);
  wbi::dds::Client<ModelRequest, ModelReply> client(client_side,
                                                    wbi::dds::topics::model_service("hum"));
  std::mt19937 rng(3);
  ModelRequest request;
  ModelReply reply;
  wbi::test::random_model_request(model, "hum", rng, {wbi::msg::GRAVITY_FORCES}, request);
  // INACTIVE: the service does not exist yet for clients.
  EXPECT_EQ(client.try_call(request, reply, 300ms), wbi::dds::CallStatus::not_connected);
  runner->activate();
  for (int i = 0; i < 20; ++i) {
    wbi::test::random_model_request(model, "hum", rng,
                                    {wbi::msg::GRAVITY_FORCES, wbi::msg::JACOBIAN}, request);
    client.call(request, reply, 10s);
    ASSERT_EQ(wbi::test::model_mismatch(model, data, request, reply), "");
  }
  // A latecomer gets the description (latched).
  wbi::dds::Subscriber<wbi::msg::RobotDescription> description(
      client_side, wbi::dds::topics::model_description("hum"), wbi::dds::qos::kLatched);
  wbi::dds::Received<wbi::msg::RobotDescription> got;
  ASSERT_TRUE(description.wait_newer(got, 0, 10s));
  EXPECT_EQ(got.sample.joint_names().size(), static_cast<std::size_t>(model.n_joints));
  EXPECT_STREQ(got.sample.joint_names()[0].c_str(), model.joint_name[0].c_str());
  EXPECT_TRUE(got.sample.floating_base());
  runner->deactivate();
  EXPECT_NE(client.try_call(request, reply, 300ms), wbi::dds::CallStatus::ok);
  runner->activate();  // serves again
  client.call(request, reply, 10s);
  EXPECT_EQ(wbi::test::model_mismatch(model, data, request, reply), "");
  runner->deactivate();
  runner->cleanup();
  runner->shutdown();
}

TEST_F(ComponentTest, BadParametersAreRejectedWithFileAndKey) {
  make();
  EXPECT_THROW(runner->configure(wbi::runtime::Parameters::from_string("robot: x")),
               wbi::runtime::TransitionError);
  EXPECT_NE(runner->last_error().find("missing parameter 'urdf'"), std::string::npos);
  EXPECT_THROW(runner->configure(wbi::runtime::Parameters::from_string("urdf: /nonexistent.urdf")),
               wbi::runtime::TransitionError);
  EXPECT_NE(runner->last_error().find("<string>:1: parameters: cannot load the model"),
            std::string::npos)
      << runner->last_error();
  EXPECT_THROW(
      runner->configure(wbi::runtime::Parameters::from_string(
          "urdf: " + wbi::test::project_model("humanoid.urdf").string() + "\nfixed: true")),
      wbi::runtime::TransitionError);
  EXPECT_NE(runner->last_error().find("unknown parameter 'fixed'"), std::string::npos);
  EXPECT_EQ(runner->state(), wbi::LifecycleState::unconfigured);
}

}  // namespace
