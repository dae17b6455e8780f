// Allocations of the remote model per call after warm-up, counted in this
// process (the model service runs in its own; the robot peer's thread is
// stopped first, so what is counted is the call: the proxy and Fast DDS).
// Fast DDS 2.9 allocates in every DataWriter::write and when it hands over a
// reply with unbounded sequences (see tests/dds_rpc/test_rpc_allocations.cpp),
// so the proxy's calls are compared with the same call made directly on a
// dds::Client: the proxy must add nothing.
#include <gtest/gtest.h>

#include <cstdio>

#include <wbi/dds/client.hpp>
#include <wbi/dds/topics.hpp>

#include "allocation_counter.hpp"
#include "remote_model_peer.hpp"

namespace {

using namespace wbi::test;

TEST(RemoteModel, AllocationsPerCallAfterWarmUp) {
  ArmPeer peer("arm_remote_alloc");
  auto service = start_model_service("arm_remote_alloc");
  auto robot = connect(remote_options("arm_remote_alloc"), kArmJoints);
  peer.stop();
  Eigen::VectorXd q = Eigen::VectorXd::Constant(7, 0.2), g(13);
  const Eigen::Vector3d gravity(0, 0, -9.81);
  const wbi::Transform base = wbi::Transform::Identity();
  for (int k = 0; k < 50; ++k) {
    robot->gravity_forces(q, base, gravity, g);
  }
  constexpr int kCalls = 200;
  long before = allocation_count();
  for (int k = 0; k < kCalls; ++k) {
    q[0] = 0.001 * k;
    robot->gravity_forces(q, base, gravity, g);
  }
  const double proxy_per_call = static_cast<double>(allocation_count() - before) / kCalls;

  // The same request on a plain client of the same service.
  wbi::dds::Participant participant("raw_client");
  wbi::dds::Client<wbi::msg::ModelRequest, wbi::msg::ModelReply> client(
      participant, wbi::dds::topics::model_service("arm_remote_alloc"));
  wbi::msg::ModelRequest request;
  wbi::msg::ModelReply reply;
  request.robot("arm_remote_alloc");
  request.state().q().assign(7, 0.2);
  request.state().dq().assign(7, 0.0);
  request.state().base_pose().orientation().w(1.0);
  request.state().gravity().z(-9.81);
  request.operations().resize(1);
  request.operations()[0].operation(wbi::msg::GRAVITY_FORCES);
  for (int k = 0; k < 50; ++k) {
    client.call(request, reply, 2s);
  }
  before = allocation_count();
  for (int k = 0; k < kCalls; ++k) {
    request.state().q()[0] = 0.001 * k;
    client.call(request, reply, 2s);
  }
  const double raw_per_call = static_cast<double>(allocation_count() - before) / kCalls;
  std::printf("allocations per gravity call (whole process): proxy %.2f, plain dds::Client %.2f\n",
              proxy_per_call, raw_per_call);
  EXPECT_LE(proxy_per_call, raw_per_call + 0.5) << "the remote model allocates per call";
}

}  // namespace
