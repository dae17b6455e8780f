// The one table of `wbi` verbs: {name, task, one-line help, example, run}, in
// the order of their tasks. A verb whose run is nullptr is planned but not
// built; `wbi VERB` then says so and exits 1.
#include <array>

#include "verb.hpp"
#include "verbs/verbs.hpp"

namespace wbi::cli {

const char* task_heading(Task task) {
  switch (task) {
    case Task::run:
      return "run: start a deployment";
    case Task::watch:
      return "watch: see what a running deployment does";
    case Task::control:
      return "control: drive a robot's controllers while it runs";
    case Task::record:
      return "record: record a run, replay it, compare and draw it";
    case Task::model:
      return "model: robot models and estimation, offline";
    case Task::robot:
      return "robot: robot configs and the plugins that bring types";
  }
  return "";
}

std::span<const Verb> verbs() {
  static const std::array<Verb, 14> table{{
      {"launch", Task::run, "start, watch and stop the processes of a deploy file",
       "wbi launch deploy/demo.yaml --duration 8", run_launch},
      {"topic", Task::watch, "list, echo and measure the topics on the DDS domain",
       "wbi topic echo wbi/arm/state --count 1", run_topic},
      {"events", Task::watch, "watch what happens in a run: faults and state changes (wbi/events)",
       "wbi events --severity warning", run_events},
      {"bridge", Task::watch, "watch and steer a run live from Foxglove or Lichtblick (WebSocket)",
       "wbi bridge    # then open ws://127.0.0.1:8765 in Foxglove", run_bridge},
      {"controller", Task::control,
       "list a robot's controllers and switch between them while it runs",
       "wbi controller switch --activate hold --deactivate pd", run_controller},
      {"param", Task::control, "list, read and set controllers' parameters while they run",
       "wbi param set pd gain_scale 0.5", run_param},
      {"record", Task::record, "record DDS topics to an MCAP file",
       "wbi record -o run.mcap --all --duration 10", run_record},
      {"play", Task::record, "replay an MCAP recording onto DDS", "wbi play run.mcap --rate 0.5",
       run_play},
      {"bag", Task::record, "inspect and compare MCAP recordings (info, compare)",
       "wbi bag info run.mcap", run_bag},
      {"render", Task::record,
       "draw a recorded run into an MP4 video or a PNG frame (offscreen, MuJoCo)",
       "wbi render run.mcap -o run.mp4", run_render},
      {"model", Task::model, "inspect and evaluate robot models (info, eval, bench, mjcf)",
       "wbi model info models/arm7.urdf", run_model},
      {"estimate", Task::model,
       "estimate joint velocities and accelerations offline from a CSV file",
       "wbi estimate --method split-kalman --input estimation/examples/encoder.csv -o dq.csv",
       run_estimate},
      {"robot", Task::robot, "check robot config files (URDF, contacts, joints, sensors)",
       "wbi robot check deploy/robots/arm.yaml", run_robot},
      {"plugins", Task::robot,
       "list the types plugins bring (components, controllers, engines) and from where",
       "wbi plugins --deploy deploy/demo.yaml", run_plugins},
  }};
  return table;
}

}  // namespace wbi::cli
