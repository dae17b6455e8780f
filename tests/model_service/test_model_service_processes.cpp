// The model service in its own process (wbi_host): 8 client processes × N
// calls with random states, every reply checked against a local computation;
// a client started before the service; the service killed mid-run (timeouts
// within the deadline, then recovery with a new service process).
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <wbi/dds/client.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/model/urdf.hpp>

#include "child_process.hpp"
#include "model_fixture.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::test::ChildProcess;
using Clock = std::chrono::steady_clock;

std::filesystem::path host() { return wbi::test::binary_dir() / "bin" / "wbi_host"; }
std::filesystem::path model_client() {
  return wbi::test::binary_dir() / "tests" / "wbi_test_model_client";
}
std::string urdf() { return wbi::test::project_model("humanoid.urdf").string(); }

std::filesystem::path host_file() {
  const auto path = wbi::test::binary_dir() / "tests" / "model_service_test.yaml";
  std::ofstream(path) << "components:\n  - name: model\n    type: model_service\n"
                         "    parameters:\n      urdf: "
                      << urdf() << "\n      robot: hum\n";
  return path;
}

long calls_per_client() {
#if defined(__SANITIZE_ADDRESS__)
  return 150;
#else
  return 1000;
#endif
}

TEST(ModelServiceProcesses, EightClientsGetCorrectRepliesOnly) {
  ChildProcess service(host(), {host_file().string()});
  ASSERT_TRUE(service.wait_for_output("wbi_host: running", 30s)) << service.output();
  const long calls = calls_per_client();
  std::vector<std::unique_ptr<ChildProcess>> clients;
  for (int c = 0; c < 8; ++c) {
    clients.push_back(std::make_unique<ChildProcess>(
        model_client(),
        std::vector<std::string>{urdf(), "hum", std::to_string(calls), std::to_string(100 + c)}));
  }
  for (int c = 0; c < 8; ++c) {
    const auto code = clients[c]->wait(std::chrono::milliseconds(240s));
    ASSERT_TRUE(code.has_value()) << "client " << c << " still running";
    EXPECT_EQ(*code, 0) << "client " << c << ": " << clients[c]->output();
    EXPECT_NE(clients[c]->output().find("model_client: ok " + std::to_string(calls)),
              std::string::npos);
  }
  EXPECT_EQ(service.stop(), 0) << service.output();
}

TEST(ModelServiceProcesses, ClientStartedBeforeTheService) {
  ChildProcess client(model_client(), {urdf(), "hum", "10", "1"});
  ASSERT_FALSE(client.wait(500ms).has_value()) << client.output();
  ChildProcess service(host(), {host_file().string()});
  const auto code = client.wait(30s);
  ASSERT_TRUE(code.has_value());
  EXPECT_EQ(*code, 0) << client.output() << service.output();
}

TEST(ModelServiceProcesses, ServiceKilledMidRunThenReplaced) {
  const auto model = wbi::model::load_urdf_file(urdf());
  wbi::model::Data data(model);
  wbi::dds::Participant participant("client");
  wbi::dds::Client<wbi::msg::ModelRequest, wbi::msg::ModelReply> client(
      participant, wbi::dds::topics::model_service("hum"));
  std::mt19937 rng(5);
  wbi::msg::ModelRequest request;
  wbi::msg::ModelReply reply;
  auto service =
      std::make_unique<ChildProcess>(host(), std::vector<std::string>{host_file().string()});
  ASSERT_TRUE(client.wait_connected(30s)) << service->output();
  for (int i = 0; i < 50; ++i) {
    wbi::test::random_model_request(model, "hum", rng, {wbi::msg::GRAVITY_FORCES}, request);
    ASSERT_EQ(client.try_call(request, reply, 5s), wbi::dds::CallStatus::ok) << "call " << i;
    ASSERT_EQ(wbi::test::model_mismatch(model, data, request, reply), "");
  }
  service->stop(9);  // SIGKILL
  service.reset();
  for (int i = 0; i < 3; ++i) {
    const auto start = Clock::now();
    EXPECT_THROW(client.call(request, reply, 200ms), wbi::dds::TimeoutError);
    EXPECT_LT(Clock::now() - start, 300ms);
  }
  ChildProcess second(host(), {host_file().string()});
  ASSERT_TRUE(second.wait_for_output("wbi_host: running", 30s)) << second.output();
  bool recovered = false;
  const auto restart = Clock::now();
  while (!recovered && Clock::now() - restart < 20s) {
    wbi::test::random_model_request(model, "hum", rng, {wbi::msg::GRAVITY_FORCES}, request);
    recovered = client.try_call(request, reply, 500ms) == wbi::dds::CallStatus::ok;
  }
  ASSERT_TRUE(recovered);
  EXPECT_EQ(wbi::test::model_mismatch(model, data, request, reply), "");
}

}  // namespace
