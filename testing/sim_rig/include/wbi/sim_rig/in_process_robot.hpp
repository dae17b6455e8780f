// A simulated robot and its estimator as components in this process, on one
// participant: the robot side of an in-process closed loop, for tests and
// benchmarks that drive a controller tick by tick (lockstep) without starting
// processes.
#pragma once

#include <optional>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/runtime/clock.hpp>
#include <wbi/runtime/registry.hpp>
#include <wbi/runtime/runner.hpp>

namespace wbi::sim_rig {

class InProcessRobot {
 public:
  // Configures a sim_robot with `sim_parameters` and an estimator with
  // `estimator_parameters` (YAML, as in a deploy file) and activates the
  // estimator. The simulation waits for start_simulation(): connect the
  // controller first (lockstep counts its commands from the first tick).
  InProcessRobot(const std::string& participant_name, const std::string& sim_parameters,
                 const std::string& estimator_parameters);
  ~InProcessRobot();  // shuts both down (runners shut down what is still running)
  InProcessRobot(const InProcessRobot&) = delete;
  InProcessRobot& operator=(const InProcessRobot&) = delete;

  void start_simulation();
  dds::Participant& participant() { return participant_; }
  runtime::ComponentRunner& sim() { return *sim_; }
  runtime::ComponentRunner& estimator() { return *estimator_; }

 private:
  dds::Participant participant_;
  runtime::SystemClock clock_;
  runtime::Registry registry_;
  // Destroyed in reverse order: the simulation stops before the estimator.
  std::optional<runtime::ComponentRunner> estimator_;
  std::optional<runtime::ComponentRunner> sim_;
};

}  // namespace wbi::sim_rig
