// Test helper process: calls the model service of ROBOT CALLS times with
// random states and checks every reply against the model library's own
// evaluation of the same URDF. Prints "model_client: ok CALLS" and exits 0,
// or prints the first failure and exits 1.
// usage: wbi_test_model_client URDF ROBOT CALLS SEED
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>

#include <wbi/dds/client.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/model/urdf.hpp>

#include "model_fixture.hpp"

int main(int argc, char** argv) {
  using namespace std::chrono_literals;
  if (argc != 5) {
    std::cerr << "usage: wbi_test_model_client URDF ROBOT CALLS SEED\n";
    return 2;
  }
  const std::string robot = argv[2];
  const long calls = std::atol(argv[3]);
  const auto model = wbi::model::load_urdf_file(argv[1]);
  wbi::model::Data data(model);
  wbi::dds::Participant participant("model_client");
  wbi::dds::Client<wbi::msg::ModelRequest, wbi::msg::ModelReply> client(
      participant, wbi::dds::topics::model_service(robot));
  if (!client.wait_connected(20s)) {
    std::cout << "model_client: not connected within 20 s" << std::endl;
    return 1;
  }
  std::mt19937 rng(static_cast<unsigned>(std::atol(argv[4])));
  const std::vector<std::vector<wbi::msg::ModelOperation>> mixes = {
      {wbi::msg::GRAVITY_FORCES},
      {wbi::msg::MASS_MATRIX, wbi::msg::BIAS_FORCES, wbi::msg::JACOBIAN, wbi::msg::JACOBIAN},
      {wbi::msg::FRAME_POSE, wbi::msg::COM, wbi::msg::DJNU, wbi::msg::COM_JACOBIAN},
      {wbi::msg::CENTROIDAL_MOMENTUM, wbi::msg::CENTROIDAL_MOMENTUM_MATRIX,
       wbi::msg::GRAVITY_FORCES}};
  wbi::msg::ModelRequest request;
  wbi::msg::ModelReply reply;
  for (long i = 0; i < calls; ++i) {
    wbi::test::random_model_request(model, robot, rng,
                                    mixes[static_cast<std::size_t>(i) % mixes.size()], request);
    try {
      client.call(request, reply, 10s);
    } catch (const std::exception& error) {
      std::cout << "model_client: call " << i << " failed: " << error.what() << std::endl;
      return 1;
    }
    if (reply.seq() != request.seq() || reply.client_id() != request.client_id()) {
      std::cout << "model_client: call " << i << ": reply of another call" << std::endl;
      return 1;
    }
    const std::string mismatch = wbi::test::model_mismatch(model, data, request, reply);
    if (!mismatch.empty()) {
      std::cout << "model_client: call " << i << ": " << mismatch << std::endl;
      return 1;
    }
  }
  std::cout << "model_client: ok " << calls << " (resent " << client.resent_requests()
            << ", dropped " << client.dropped_replies() << " replies of other clients)"
            << std::endl;
  return 0;
}
