#include "dds_state.hpp"

#include <wbi/msg/eigen.hpp>

#include "size_check.hpp"

namespace wbi::proxy {

DdsState::DdsState(RobotConnection& robot)
    : robot_(robot),
      parameters_(robot.participant, dds::topics::estimator_parameters(robot.options.robot),
                  dds::qos::kCommand) {}

// One read of the newest estimate, every field gathered from it: the fields
// cannot belong to different samples, so there is nothing to retry.
Stamp DdsState::read_robot_state(RobotState& out, ReadMode mode) {
  robot_.require_init();
  const auto n = static_cast<Eigen::Index>(robot_.controlled.size());
  for (auto* v : {&out.q, &out.dq, &out.ddq}) {
    if (v->size() != n) {
      v->resize(n);  // the first call only
    }
  }
  read_state(kRobotStateRead, mode, [&](const wbi::msg::StateEstimate& estimate) {
    robot_.gather(estimate.q(), 0, static_cast<int>(n), out.q, "joint position estimates");
    robot_.gather(estimate.dq(), 0, static_cast<int>(n), out.dq, "joint velocity estimates");
    robot_.gather(estimate.ddq(), 0, static_cast<int>(n), out.ddq, "joint acceleration estimates");
    msg::to_transform(estimate.base_pose(), out.world_H_base);
    out.base_velocity = msg::to_eigen(estimate.base_velocity());
  });
  out.stamp = robot_.state.stamp();
  return out.stamp;
}

Stamp DdsState::read_estimates(EstimateKind kind, VectorRef values, ReadMode mode) {
  robot_.require_init();
  const int count = estimate_count(kind);
  check_size("estimate values", values.size(), count * estimate_width(kind));
  return read_range(kind, 0, count, values, mode);
}

Stamp DdsState::read_estimate(EstimateKind kind, int index, VectorRef values, ReadMode mode) {
  robot_.require_init();
  check_index("estimate", index, estimate_count(kind));
  check_size("estimate values", values.size(), estimate_width(kind));
  return read_range(kind, index, 1, values, mode);
}

Stamp DdsState::read_base_pose(Transform& world_H_base, ReadMode mode) {
  robot_.require_init();
  read_state(static_cast<std::size_t>(EstimateKind::base_pose), mode,
             [&](const wbi::msg::StateEstimate& estimate) {
               msg::to_transform(estimate.base_pose(), world_H_base);
             });
  return robot_.state.stamp();
}

const IdList& DdsState::external_wrench_links() const {
  robot_.require_init();
  return robot_.external_wrench_links;
}

// "fixed_link" takes the link's index in frame_list() and travels by name.
void DdsState::set_estimation_parameter(const std::string& name, double value) {
  robot_.require_init();
  wbi::msg::EstimatorParameter parameter;
  parameter.header().robot(robot_.options.robot);
  parameter.header().stamp_ns(system_now_ns());
  parameter.name(name);
  parameter.value(value);
  if (name == "fixed_link" && model_ != nullptr) {
    const auto& frames = model_->frame_list();
    const int frame = static_cast<int>(value);
    check_index("fixed_link frame", frame, static_cast<int>(frames.size()));
    parameter.text(frames[static_cast<std::size_t>(frame)]);
  }
  if (!parameters_.publish(parameter)) {
    throw Error("estimator parameter '" + name + "' for robot '" + robot_.options.robot +
                "' not sent");
  }
}

int DdsState::estimate_count(EstimateKind kind) const {
  return wbi::estimate_count(kind, static_cast<int>(robot_.controlled.size()),
                             static_cast<int>(robot_.force_torque_names.size()),
                             static_cast<int>(robot_.external_wrench_links.size()));
}

Stamp DdsState::read_range(EstimateKind kind, int first, int count, VectorRef out, ReadMode mode) {
  read_state(static_cast<std::size_t>(kind), mode, [&](const wbi::msg::StateEstimate& state) {
    read_sample(state, kind, first, count, out);
  });
  return robot_.state.stamp();
}

void DdsState::read_sample(const wbi::msg::StateEstimate& state, EstimateKind kind, int first,
                           int count, VectorRef out) const {
  switch (kind) {
    case EstimateKind::joint_position:
      robot_.gather(state.q(), first, count, out, "joint position estimates");
      break;
    case EstimateKind::joint_velocity:
      robot_.gather(state.dq(), first, count, out, "joint velocity estimates");
      break;
    case EstimateKind::joint_acceleration:
      robot_.gather(state.ddq(), first, count, out, "joint acceleration estimates");
      break;
    case EstimateKind::joint_torque:
      robot_.gather(state.tau(), first, count, out, "joint torque estimates");
      break;
    case EstimateKind::base_pose:
      msg::to_coordinates(state.base_pose(), out.head<7>());
      break;
    case EstimateKind::base_velocity:
      out = msg::to_eigen(state.base_velocity());
      break;
    case EstimateKind::base_acceleration:
      out = msg::to_eigen(state.base_acceleration());
      break;
    case EstimateKind::force_torque:
      if (state.force_torque().size() < static_cast<std::size_t>(first + count)) {
        throw Error("force_torque estimates: the state of robot '" + robot_.options.robot +
                    "' carries " + std::to_string(state.force_torque().size()) + " of its " +
                    std::to_string(robot_.force_torque_names.size()) +
                    " F/T sensors (the estimator component fills them from the sensor "
                    "samples; read_sensors(force_torque) has the raw readings)");
      }
      for (int i = 0; i < count; ++i) {
        msg::to_eigen(state.force_torque().at(static_cast<std::size_t>(first + i)),
                      out.segment<6>(6 * i));
      }
      break;
    case EstimateKind::external_wrench:
      if (state.external_wrenches().size() < static_cast<std::size_t>(first + count)) {
        throw Error("external_wrench estimates: the state of robot '" + robot_.options.robot +
                    "' carries " + std::to_string(state.external_wrenches().size()) +
                    " external wrenches, init() saw " +
                    std::to_string(robot_.external_wrench_links.size()) +
                    " (the estimator was reconfigured?)");
      }
      for (int i = 0; i < count; ++i) {
        msg::to_eigen(state.external_wrenches().at(static_cast<std::size_t>(first + i)).wrench(),
                      out.segment<6>(6 * i));
      }
      break;
  }
}

}  // namespace wbi::proxy
