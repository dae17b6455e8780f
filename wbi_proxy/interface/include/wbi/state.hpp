// The State element: measured or estimated quantities of the robot.
#pragma once

#include <string>

#include "wbi/types.hpp"

namespace wbi {

class State {
 public:
  virtual ~State() = default;

  // All values of a kind, stacked (see EstimateKind for the sizes), or one
  // (a joint, or an F/T sensor). Throws StaleDataError when there is no
  // estimate, or it is too old.
  virtual Stamp read_estimates(EstimateKind kind, VectorRef values,
                               ReadMode mode = ReadMode::latest) = 0;
  virtual Stamp read_estimate(EstimateKind kind, int index, VectorRef values,
                              ReadMode mode = ReadMode::latest) = 0;

  // q, dq, ddq, base pose and base velocity of one and the same estimate, in
  // one call: what a control tick reads. Sizes the vectors to dofs() when they
  // differ (the first call); allocates nothing after that. Blocking mode waits
  // for an estimate newer than the previous read_robot_state, up to the
  // interface's bound, then throws TimeoutError; StaleDataError as below.
  virtual Stamp read_robot_state(RobotState& state, ReadMode mode = ReadMode::latest) = 0;

  // The links the estimator estimates an external wrench on (EstimateKind::
  // external_wrench), as its first estimate at init() named them; empty unless
  // it estimates joint torques from F/T sensors (joint_torques: force_torque).
  virtual const IdList& external_wrench_links() const = 0;

  // The base pose as a homogeneous transform.
  virtual Stamp read_base_pose(Transform& world_H_base, ReadMode mode = ReadMode::latest) = 0;

  // Changes a parameter of the estimator: "fixed_link" (value: the link's
  // index in frame_list()), "reset", or a parameter of its method (e.g.
  // "process_noise"). The estimator reports a parameter it rejects.
  virtual void set_estimation_parameter(const std::string& name, double value) = 0;
};

}  // namespace wbi
