// The model-service component (type "model_service"): loads a URDF, publishes
// the robot description latched on wbi/<robot>/description and answers model
// requests on the service wbi/<robot>/model (topics::model_service) with an
// Evaluator: any set of the model library's quantities at one state, in one
// reply; bad requests get an error reply naming the problem.
//
// Parameters
//   urdf           string: URDF file; a relative path is looked up beside the
//                  host file first, then from the working directory
//   robot_config   string, instead of urdf: a robot config file
//                  (robot_side/robot_config): its URDF, fixed_base and every
//                  joint's armature, as the simulation of that file has them
//   robot          string, default the URDF's robot name: the name in topics
//                  and requests
//   joints         list of strings, default all movable joints: a reduced
//                  model (the other joints locked at 0)
//   fixed_base     bool, default false
//   armature       map joint: value, default none (or the robot config's, which
//                  this overrides joint by joint): the rotor inertia reflected
//                  through the gear ratio [kg·m² or kg] (wbi/model/model.hpp);
//                  an unknown or fixed joint, a negative or non-finite value fail
//                  configure naming `armature` and the joint
//   backend        string, default "wbi": the dynamics library that computes,
//                  "wbi" or "dart" (when built; wbi/model/backend.hpp)
//   worker_thread  bool, default false: compute on the service's worker thread
//                  instead of the DDS thread that received the request
//
// Lifecycle: on_configure loads the model and publishes the description;
// on_activate starts serving (the service's endpoints exist only while
// ACTIVE, so a client never meets a half-started service: it waits, within
// its deadline, to be connected); on_deactivate stops serving. No periodic
// cycle (rate_hz 0).
#pragma once

#include <memory>
#include <string>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/server.hpp>
#include <wbi/model/model.hpp>
#include <wbi/runtime/component.hpp>
#include <wbi/runtime/registry.hpp>

#include "wbi/model_service/evaluator.hpp"

namespace wbi::model_service {

class ModelServiceComponent final : public runtime::Component {
 public:
  ModelServiceComponent();
  ~ModelServiceComponent() override;

  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override;
  void on_activate() override;
  void on_deactivate() override;
  void on_cleanup() override { release(); }
  void on_shutdown() override { release(); }

  // After configure: the served robot and the server's statistics.
  const std::string& robot() const { return robot_; }
  dds::ServerStats stats() const;

 private:
  void release();

  std::string robot_;
  dds::Participant* participant_ = nullptr;
  bool worker_thread_ = false;
  std::unique_ptr<model::ModelBackend> model_;
  std::unique_ptr<Evaluator> evaluator_;
  std::unique_ptr<dds::Publisher<msg::RobotDescription>> description_;
  std::unique_ptr<dds::Server<msg::ModelRequest, msg::ModelReply>> server_;
};

// Registers "model_service".
void register_components(runtime::Registry& registry);

}  // namespace wbi::model_service
