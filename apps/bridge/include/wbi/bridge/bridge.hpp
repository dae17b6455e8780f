// `wbi bridge`: a deployment seen and steered live from Foxglove (or
// Lichtblick) through the Foxglove WebSocket protocol.
//
// - Every wbi topic on the domain is a channel: encoding "cdr", its OMG IDL as
//   schema (schemaEncoding "omgidl", schemaName the DDS type name, as `wbi
//   record` writes them into MCAP); samples are forwarded as their CDR bytes,
//   never decoded. Channels are unadvertised when their topic loses its last
//   writer and advertised again (same id) when it has one.
// - wbi/<robot>/transforms (JSON foxglove.FrameTransforms, one transform per
//   URDF link) from the state estimate (or the ground truth), at most
//   transforms_rate_hz; "/robot_description" carries the URDF for Foxglove's
//   URDF layer and fetchAsset serves its meshes.
// - Parameters: the hosted controllers' declared parameters; services: list
//   and switch controllers (controller_hosts.hpp, services.hpp).
// - clientPublish on controllers' reference inputs only; raw actuator
//   commands only with allow_commands (client_publish.hpp).
// - Back-pressure: each client has a bounded queue; a slow client loses its
//   oldest data messages, is told how many in a status message once a second,
//   and never slows the DDS readers or the other clients.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <wbi/dds/participant.hpp>

namespace wbi::bridge {

struct BridgeOptions {
  std::string address = "127.0.0.1";  // loopback by default: a bridge steers a robot
  std::uint16_t port = 8765;          // 0: any free port
  std::size_t client_queue_bytes = 8u << 20;
  std::size_t max_client_message_bytes = 1u << 20;
  std::string robot;  // empty: every robot with a description on the domain
  std::string urdf;   // empty: the path in each robot's description
  std::vector<std::string> mesh_paths;
  double transforms_rate_hz = 30.0;
  bool transforms_from_ground_truth = false;
  // Accept raw actuator commands from clients (wbi/<robot>/commands); off:
  // clients publish only on controllers' reference inputs.
  bool allow_commands = false;
  std::chrono::nanoseconds call_timeout = std::chrono::seconds(2);
};

struct BridgeCounts {
  std::size_t clients = 0;
  std::size_t channels = 0;     // advertised now
  std::uint64_t forwarded = 0;  // data messages queued to a client
};

class Bridge {
 public:
  using Log = std::function<void(const std::string& line)>;

  // Listens at once; throws std::runtime_error when the address cannot be bound.
  Bridge(dds::Participant& participant, BridgeOptions options, Log log);
  ~Bridge();
  Bridge(const Bridge&) = delete;
  Bridge& operator=(const Bridge&) = delete;

  std::uint16_t port() const;
  // Follows discovery: new topics and robots, topics that lost their writers.
  // Call it periodically (wbi bridge: every 200 ms).
  void discover();
  BridgeCounts counts() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace wbi::bridge
