// A controller as the host holds it (controller_host.hpp): its tables,
// inputs and outputs, the joints it commands, its chains and its state.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "joint_set_interface.hpp"
#include "wbi/controllers/controller_host.hpp"

namespace wbi::controllers {

struct ControllerHost::Hosted {
  std::string name, type;
  std::unique_ptr<Controller> controller;
  std::unique_ptr<ParameterTable> parameters;
  std::unique_ptr<JointSetInterface> view;                // what it is configured on
  std::vector<std::unique_ptr<ReferenceInput>> inputs;    // one per declared reference
  std::vector<std::unique_ptr<ReferenceOutput>> outputs;  // one per declared output
  std::vector<std::uint64_t> stale_said;                  // per input: episodes printed
  std::vector<char> chained;                              // per input: fed by an output here
  std::vector<int> joints;                                // the host's joints it commands
  std::vector<Hosted*> upstream, downstream;              // the chains: who feeds it, whom it feeds
  bool configured = false;
  bool active = false;
  bool ran = false;  // was active at least once: its summary is printed
  int overruns_in_a_row = 0;
  std::string configure_error = "not configured";

  // Whether its outputs reach `other`, directly or through others.
  bool feeds(const Hosted& other) const {
    for (const Hosted* next : downstream) {
      if (next == &other || next->feeds(other)) {
        return true;
      }
    }
    return false;
  }
  bool shares_joints(const Hosted& other) const {
    for (const int j : joints) {
      for (const int k : other.joints) {
        if (j == k) {
          return true;
        }
      }
    }
    return false;
  }
};

inline bool ControllerHost::is_running(const Hosted& hosted) const {
  return &hosted == hold_ ? hold_active_ : hosted.active;
}

}  // namespace wbi::controllers
