// The model service with `backend: dart`: the evaluator's replies and the
// component's replies over DDS equal the model library's own evaluation (1e-9
// relative, tests/model_service/model_fixture.hpp); a bad backend name is
// rejected naming the parameter.
#include <gtest/gtest.h>

#include <chrono>

#include <wbi/dds/client.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/model_service/component.hpp>
#include <wbi/runtime/runner.hpp>

#include "backend_test_common.hpp"
#include "model_fixture.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::msg::ModelReply;
using wbi::msg::ModelRequest;

TEST(ServiceBackend, DartEvaluatorMatchesTheLibrary) {
  if (!wbi::test::dart_built()) {
    GTEST_SKIP() << wbi::test::kDartMissing;
  }
  for (const char* file : {"humanoid.urdf", "arm7.urdf"}) {
    const std::string urdf = wbi::test::project_model(file).string();
    auto dart = wbi::model::make_model_backend("dart", urdf);
    const wbi::model::Model& model = dart->model();
    wbi::model::Data data(model);
    wbi::model_service::Evaluator evaluator(*dart, "robot");
    std::mt19937 rng(11);
    ModelRequest request;
    ModelReply reply;
    for (int round = 0; round < 10; ++round) {
      wbi::test::random_model_request(model, "robot", rng, wbi::test::every_model_operation(),
                                      request);
      evaluator.evaluate(request, reply);
      ASSERT_EQ(wbi::test::model_mismatch(model, data, request, reply), "")
          << file << ", round " << round;
    }
  }
}

struct ServiceBackendComponent : ::testing::Test {
  wbi::dds::Participant service_side{"service"};
  wbi::dds::Participant client_side{"client"};
  wbi::runtime::SystemClock clock;
  wbi::runtime::ComponentRunner runner{
      std::make_unique<wbi::model_service::ModelServiceComponent>(),
      wbi::runtime::ComponentContext{"model", "model_service", &service_side, &clock}};
};

TEST_F(ServiceBackendComponent, ServesWithTheDartBackend) {
  if (!wbi::test::dart_built()) {
    GTEST_SKIP() << wbi::test::kDartMissing;
  }
  const std::string urdf = wbi::test::project_model("humanoid.urdf").string();
  runner.configure(
      wbi::runtime::Parameters::from_string("urdf: " + urdf + "\nrobot: hum\nbackend: dart"));
  runner.activate();
  const auto model = wbi::model::load_urdf_file(urdf);
  wbi::model::Data data(model);
  wbi::dds::Client<ModelRequest, ModelReply> client(client_side,
                                                    wbi::dds::topics::model_service("hum"));
  std::mt19937 rng(3);
  ModelRequest request;
  ModelReply reply;
  for (int i = 0; i < 5; ++i) {
    wbi::test::random_model_request(model, "hum", rng, wbi::test::every_model_operation(), request);
    client.call(request, reply, 10s);
    ASSERT_EQ(wbi::test::model_mismatch(model, data, request, reply), "") << "call " << i;
  }
  runner.deactivate();
  runner.cleanup();
  runner.shutdown();
}

TEST_F(ServiceBackendComponent, UnknownBackendIsRejectedNamingTheParameter) {
  const std::string urdf = wbi::test::project_model("humanoid.urdf").string();
  EXPECT_THROW(runner.configure(
                   wbi::runtime::Parameters::from_string("urdf: " + urdf + "\nbackend: pinocchio")),
               wbi::runtime::TransitionError);
  EXPECT_NE(runner.last_error().find("backend"), std::string::npos) << runner.last_error();
  EXPECT_NE(runner.last_error().find("unknown model backend 'pinocchio'"), std::string::npos)
      << runner.last_error();
  EXPECT_EQ(runner.state(), wbi::LifecycleState::unconfigured);
}

}  // namespace
