// The one table of `wbi` verbs: {name, one-line help, run}. A verb whose run is
// nullptr is planned but not built; `wbi VERB` then says so and exits 1.
#include <array>

#include "verb.hpp"
#include "verbs/verbs.hpp"

namespace wbi::cli {

std::span<const Verb> verbs() {
  static const std::array<Verb, 14> table{{
      {"launch", "start, watch and stop the processes of a deploy file", run_launch},
      {"record", "record DDS topics to an MCAP file", run_record},
      {"play", "replay an MCAP recording onto DDS", run_play},
      {"bag", "inspect and compare MCAP recordings (info, compare)", run_bag},
      {"render", "draw a recorded run into an MP4 video or a PNG frame (offscreen, MuJoCo)",
       run_render},
      {"topic", "list, echo and measure the topics on the DDS domain", run_topic},
      {"events", "watch what happens in a run: faults and state changes (wbi/events)", run_events},
      {"controller", "list a robot's controllers and switch between them while it runs",
       run_controller},
      {"param", "list, read and set controllers' parameters while they run", run_param},
      {"bridge", "watch and steer a run live from Foxglove or Lichtblick (WebSocket)", run_bridge},
      {"plugins", "list the types plugins bring (components, controllers, engines) and from where",
       run_plugins},
      {"model", "inspect and evaluate robot models (info, eval, bench)", run_model},
      {"robot", "check robot config files (URDF, contacts, joints, sensors)", run_robot},
      {"estimate", "estimate joint velocities and accelerations offline from a CSV file",
       run_estimate},
  }};
  return table;
}

}  // namespace wbi::cli
