// `lab_posture_planner`: a component (in any process) that publishes a slow,
// smooth posture (posture_trajectory.hpp) to a controller's reference input
// wbi/<robot>/references/<controller>/<input>, one point per state the
// robot's estimator publishes, as wbi's own com_sinusoid generator does.
//
// It reads the state like a controller but claims no joint. Its time is the
// robot's since the first state it reads; the posture it starts from is that
// state's. In lockstep it is started before the controller (deploy/lab_arm.yaml),
// so that its first state is the simulation's first: the planner and the host
// then count time from the same tick. Once it knows the robot's period (two
// states) it also sends the next state's point ahead, so that a host waiting
// for its points (reference_wait_s) rarely waits.
//
// Parameters: the whole-body interface's (robot, urdf, model, max_age_s, …:
// wbi/controllers/interface_options.hpp), and
//   joints             required; the joints the input's values are for, in order
//   controller         required; the controller whose input it feeds
//   input              the input's name (default posture)
//   target             required; one per joint [rad]
//   start_s, move_s    the move to the target: when it begins, how long it takes
//                      (defaults 1.5 s, 2 s)
//   sway_amplitude     one per joint [rad] (default none), sway_frequency_hz
//                      (default 0.5), sway_periods (default 1): the sway about
//                      the target once it is reached
//   state_timeout_s    longest wait for a new state (default 0.005 s)
//   init_timeout_s     wait for the robot's components (default 30 s)
// At shutdown it prints how many points it sent.
#pragma once

#include <cstdint>
#include <memory>

#include <wbi/runtime/component.hpp>
#include <wbi/whole_body_interface.hpp>

#include "posture_trajectory.hpp"

namespace wbi::controllers {
class ReferenceWriter;
}

namespace lab {

class LabPosturePlanner final : public wbi::runtime::Component {
 public:
  LabPosturePlanner();
  ~LabPosturePlanner() override;

  void on_configure(const wbi::runtime::Parameters& parameters,
                    const wbi::runtime::ComponentContext& context) override;
  void on_shutdown() override;

  // A cycle per new state (and, while the robot waits at its first state,
  // per state_timeout_s: see update()).
  bool event_driven() const override { return true; }
  bool wait_for_event(std::int64_t timeout_ns) override;
  void update(std::int64_t time_ns, std::int64_t period_ns) override;

 private:
  void read_trajectory(const wbi::runtime::Parameters& parameters, int joints);
  void send(std::int64_t stamp_ns);  // the point for that robot time

  std::unique_ptr<wbi::WholeBodyInterface> robot_;
  std::unique_ptr<wbi::controllers::ReferenceWriter> writer_;
  wbi::RobotState state_;
  PostureTrajectory trajectory_;
  Eigen::VectorXd x_, v_, a_;  // [n] the point being sent

  std::int64_t start_ns_ = -1;       // stamp of the first state: t = 0
  std::int64_t last_state_ns_ = -1;  // of the newest state read
  std::int64_t last_sent_ns_ = -1;   // of the newest point sent
  std::int64_t step_ns_ = 0;         // the robot's period: the smallest step between states
  std::uint64_t states_ = 0;         // states read since the start
  std::uint64_t first_again_ = 0;    // the first point sent again
};

}  // namespace lab
