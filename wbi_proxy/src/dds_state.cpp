#include "dds_state.hpp"

#include <Eigen/Geometry>

#include "size_check.hpp"

namespace wbi::proxy {

namespace {

void to_transform(const wbi::msg::Pose& pose, Transform& world_H_base) {
  const Eigen::Quaterniond orientation(pose.orientation().w(), pose.orientation().x(),
                                       pose.orientation().y(), pose.orientation().z());
  world_H_base.setIdentity();
  world_H_base.topLeftCorner<3, 3>() = orientation.normalized().toRotationMatrix();
  world_H_base.topRightCorner<3, 1>() << pose.position().x(), pose.position().y(),
      pose.position().z();
}

}  // namespace

DdsState::DdsState(RobotConnection& robot)
    : robot_(robot),
      parameters_(robot.participant, dds::topics::estimator_parameters(robot.options.robot),
                  dds::qos::kCommand) {}

const wbi::msg::StateEstimate& DdsState::take(std::size_t read, ReadMode mode) {
  return robot_.state.take(read, mode, robot_.options.max_age_s,
                           robot_.options.blocking_read_timeout);
}

// One take of the newest estimate, every field gathered from it: the fields
// cannot belong to different samples, so there is nothing to retry.
Stamp DdsState::read_robot_state(RobotState& out, ReadMode mode) {
  robot_.require_init();
  const auto n = static_cast<Eigen::Index>(robot_.controlled.size());
  for (auto* v : {&out.q, &out.dq, &out.ddq}) {
    if (v->size() != n) {
      v->resize(n);  // the first call only
    }
  }
  const auto& estimate = take(kRobotStateRead, mode);
  robot_.gather(estimate.q(), 0, static_cast<int>(n), out.q, "joint position estimates");
  robot_.gather(estimate.dq(), 0, static_cast<int>(n), out.dq, "joint velocity estimates");
  robot_.gather(estimate.ddq(), 0, static_cast<int>(n), out.ddq, "joint acceleration estimates");
  to_transform(estimate.base_pose(), out.world_H_base);
  out.base_velocity =
      Eigen::Map<const Eigen::Matrix<double, 6, 1>>(estimate.base_velocity().data());
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
  to_transform(take(static_cast<std::size_t>(EstimateKind::base_pose), mode).base_pose(),
               world_H_base);
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
  const auto& state = take(static_cast<std::size_t>(kind), mode);
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
    case EstimateKind::base_pose: {
      const auto& p = state.base_pose();
      out << p.position().x(), p.position().y(), p.position().z(), p.orientation().w(),
          p.orientation().x(), p.orientation().y(), p.orientation().z();
      break;
    }
    case EstimateKind::base_velocity:
      out = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(state.base_velocity().data());
      break;
    case EstimateKind::base_acceleration:
      out = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(state.base_acceleration().data());
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
        const auto& w = state.force_torque().at(static_cast<std::size_t>(first + i));
        out.segment<6>(6 * i) << w.force().x(), w.force().y(), w.force().z(), w.torque().x(),
            w.torque().y(), w.torque().z();
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
        const auto& w = state.external_wrenches().at(static_cast<std::size_t>(first + i)).wrench();
        out.segment<6>(6 * i) << w.force().x(), w.force().y(), w.force().z(), w.torque().x(),
            w.torque().y(), w.torque().z();
      }
      break;
  }
  return robot_.state.stamp();
}

}  // namespace wbi::proxy
