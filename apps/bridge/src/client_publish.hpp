// The protocol's clientPublish, limited to what a viewer may steer:
// - a controller's declared reference input, wbi/<robot>/references/<controller>/<input>
//   (its host reads it: a reader is on the domain), as CDR of
//   wbi::msg::TrajectoryPoint or as JSON {"position": [...], "velocity": [...],
//   "acceleration": [...], "stamp_ns": N} (Foxglove's Publish panel); a JSON point
//   without stamp_ns is for the robot's newest state;
// - raw actuator commands (wbi/<robot>/commands, CDR) only with --allow-commands,
//   and each client that advertises them is logged.
// Anything else is refused with a line that says what is allowed.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <string>

#include <wbi/dds/participant.hpp>

#include "protocol.hpp"
#include "websocket_server.hpp"

namespace wbi::dds {
class RawPublisher;
}

namespace wbi::bridge {

class ClientPublish {
 public:
  // newest_state_stamp(robot): the stamp a JSON point without one is for (0: none yet).
  ClientPublish(dds::Participant& participant, bool allow_commands,
                std::function<std::int64_t(const std::string& robot)> newest_state_stamp);
  ~ClientPublish();

  // The refusal, or empty when the channel is taken. Logs command publishers.
  std::string advertise(ClientId client, const protocol::ClientChannel& channel,
                        const std::function<void(const std::string&)>& log);
  void unadvertise(ClientId client, std::uint32_t channel_id);
  void forget(ClientId client);
  // The refusal, or empty when published.
  std::string publish(ClientId client, std::uint32_t channel_id,
                      std::span<const std::uint8_t> payload);

 private:
  struct Target;
  std::shared_ptr<dds::RawPublisher> writer_for(const std::string& topic, const std::string& type);

  dds::Participant& participant_;
  const bool allow_commands_;
  std::function<std::int64_t(const std::string&)> newest_state_stamp_;
  std::mutex mutex_;
  std::map<std::pair<ClientId, std::uint32_t>, std::shared_ptr<Target>> channels_;
  std::map<std::string, std::weak_ptr<dds::RawPublisher>> writers_;  // by topic, shared by clients
};

}  // namespace wbi::bridge
