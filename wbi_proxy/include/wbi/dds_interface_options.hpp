// The options of the DDS proxy (make_dds_interface, wbi/dds_interface.hpp):
// which robot, which model, how fresh the data must be, which DDS domain.
// Apart from the factory so that each element of the proxy takes the options
// without the whole interface.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/producers.hpp>

namespace wbi {

// Every member has a default (designated initializers name only what differs:
// make_dds_interface({.robot = "arm", .urdf = path})).
struct DdsInterfaceOptions {
  std::string robot;                      // robot name: topics wbi/<robot>/…
  std::string controller = "controller";  // sender name in commands (one owner per joint)
  // Joint claims (components/robot/README.md, "Joint claims"): init() claims the
  // controlled joints from the robot before any command, and fails naming each
  // joint another controller holds; close() releases them. `force` takes them
  // from their owner (a supervisor, an e-stop tool: logged, the owner is told).
  // none: no claim, for a proxy that only reads (its commands would be refused
  // on joints others hold) or a robot that answers no claims.
  enum class Claim { claim, force, none };
  Claim claim = Claim::claim;

  enum class ModelSource { local, remote };
  ModelSource model_source = ModelSource::local;
  // Local model: the robot's URDF (required). Remote model: optional, only for
  // frame_list() (else the model service's URDF path, when readable here).
  std::string urdf;
  // Local model: the dynamics library that computes, "wbi" or "dart" (when built;
  // wbi/model/backend.hpp). The controller does not change.
  std::string local_model_backend = "wbi";
  // Local model: armature by joint name (the rotor inertia reflected through the
  // gear ratio, wbi/model/model.hpp), as the robot's model service is given it.
  // A remote model has the service's own.
  std::map<std::string, double> armature{};

  // Positions of the robot's joints outside the controlled list, for the model.
  // A joint not listed here is locked where init() measures it.
  std::map<std::string, double> locked_positions{};

  // The raw sensor samples (wbi/<robot>/sensors) are subscribed to only when
  // read: by the first read_sensors/read_sensor of a kind that travels in them
  // (it waits up to blocking_read_timeout for the first sample), or, when
  // true, from construction on, and init() waits for them too. A controller
  // that reads only the state never receives them.
  bool read_sensors = false;

  double max_age_s = 0.1;  // reads fail on samples older than this
  std::chrono::milliseconds blocking_read_timeout{1000};
  // Deadline of a remote model call (the model service at wbi/<robot>/model).
  std::chrono::milliseconds model_timeout{200};

  dds::ParticipantOptions participant{};  // domain, discovery, QoS file
  // When set, the interface's endpoints join this participant (a host's, which
  // must outlive the interface) and `participant` is not used. A process with
  // one secured participant, not two created at the same instant: Fast DDS
  // 2.9.1 can leave the DDS Security handshake of one of two participants
  // discovered at once unfinished for good (dds/README.md, "DDS Security").
  dds::Participant* shared_participant = nullptr;

  // The robot's streams (description, sensors, state, model replies) are each
  // taken from one writer (wbi/dds/producers.hpp); this hears the samples of
  // any other writer being dropped, e.g. to count them in a component's status
  // (runtime::count_producer_events). Called on DDS threads.
  std::function<void(const dds::ProducerEvent&)> on_producer_event{};
};

}  // namespace wbi
