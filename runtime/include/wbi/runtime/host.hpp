// Host: runs the components a YAML host file lists, in one process, sharing
// one DDS participant and one clock.
//
//   # robot.yaml
//   domain_id: 3              # optional; WBI_DOMAIN_ID wins (else 0)
//   clock: system             # system | simulation (wbi/clock)
//   status_period_s: 1.0      # heartbeat period on wbi/status
//   plugins: [my_lab]         # loaded before the components are made, by the
//                             # program (plugins.hpp; the registry passed here
//                             # already has their types)
//   components:
//     - name: model           # instance name, unique
//       type: model_service   # a registered type
//       rate_hz: 0            # periodic cycle rate; 0 / absent: none
//       parameters:           # the component's own parameters
//         urdf: models/humanoid.urdf
//
// Every error names the file and line: unknown keys, wrong types, missing or
// duplicate names, unknown types, and the components' own parameter errors.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "wbi/runtime/parameters.hpp"
#include "wbi/runtime/registry.hpp"
#include "wbi/runtime/runner.hpp"

namespace YAML {
class Node;
}

namespace wbi::dds {
class Participant;
struct ParticipantOptions;
}  // namespace wbi::dds

namespace wbi::runtime {

// Reads a host document's placement blocks into the participant's options,
// for the process named `identity` (wbi_host passes the deploy reader's,
// wbi::deploy::read_placement; for processes of a deploy file, the join keys
// that file's reader read, domain and QoS file included, and no keys of the
// document). Injected, so that the runtime neither depends
// on the deploy-file reader nor knows its keys: `keys` names the top-level
// keys `read` handles, which the host file's unknown-key check accepts besides
// the runtime's own. It produces join options; the runtime uses them.
struct PlacementReader {
  std::vector<std::string> keys;
  std::function<void(const YAML::Node& root, const std::string& file, const std::string& identity,
                     dds::ParticipantOptions& options)>
      read;
  // A reader without `read` is none: its keys are not accepted either.
  explicit operator bool() const { return static_cast<bool>(read); }
};

// The participant joins as dds/README.md "Joining a deployment" says:
// defaults < the file (domain_id, qos_file, the placement reader's blocks) < WBI_* environment.
// Reads a host file (for its `plugins:` before the Host is made). Throws
// ParameterError naming the file (and line).
YAML::Node read_host_file(const std::string& file);

class Host {
 public:
  // Reads the file and creates the participant, the clock and the components
  // (UNCONFIGURED). Throws ParameterError (bad file) or std::invalid_argument.
  // Without a placement reader, the keys one would read are unknown keys.
  Host(const std::string& file, const Registry& registry, PlacementReader placement = {});
  // From a host document already parsed, e.g. one process of a deploy file
  // (wbi::deploy::load_process_host: the runtime does not read the deploy
  // format). `file` names it in errors and anchors its relative paths;
  // `identity` is the process's name (the placement reader's default identity).
  Host(const YAML::Node& document, const std::string& file, const std::string& identity,
       const Registry& registry, PlacementReader placement = {});
  // Same, from YAML text; `file` names it in messages.
  static std::unique_ptr<Host> from_string(const std::string& yaml, const Registry& registry,
                                           const std::string& file = "<string>",
                                           PlacementReader placement = {});
  ~Host();  // stop()
  Host(const Host&) = delete;
  Host& operator=(const Host&) = delete;

  // Configures then activates every component in file order. On a failure,
  // stops those already started and throws TransitionError / ParameterError.
  void start();
  // Deactivates, cleans up and shuts down every component, in reverse order.
  // Never throws; returns the errors met, one line each.
  std::vector<std::string> stop();

  std::size_t size() const { return components_.size(); }
  ComponentRunner& component(const std::string& instance);
  dds::Participant& participant() { return *participant_; }
  Clock& clock() { return *clock_; }

 private:
  struct Entry {
    std::unique_ptr<ComponentRunner> runner;
    Parameters parameters;
  };
  Host() = default;
  void load(const std::string& yaml_or_file, bool is_text, const std::string& file,
            const Registry& registry, const PlacementReader& placement = {});
  void build(const YAML::Node& root, const std::string& file, const std::string& identity,
             const Registry& registry, const PlacementReader& placement, bool paths_from_file);

  std::unique_ptr<dds::Participant> participant_;
  std::unique_ptr<Clock> clock_;
  std::vector<Entry> components_;
};

}  // namespace wbi::runtime
