#include "frame_transforms.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

#include <wbi/model/configuration.hpp>
#include <wbi/model/kinematics.hpp>
#include <wbi/model/urdf.hpp>

namespace wbi::bridge {

namespace {

using nlohmann::json;

model::Model load(const std::string& urdf_path, bool floating_base) {
  model::LoadOptions options;
  options.fixed_base = !floating_base;
  return model::load_urdf_file(urdf_path, options);
}

json transform_json(const json& timestamp, const std::string& parent, const std::string& child,
                    const Eigen::Matrix4d& parent_H_child) {
  const Eigen::Quaterniond rotation(Eigen::Matrix3d(parent_H_child.topLeftCorner<3, 3>()));
  const Eigen::Vector3d translation = parent_H_child.topRightCorner<3, 1>();
  return {{"timestamp", timestamp},
          {"parent_frame_id", parent},
          {"child_frame_id", child},
          {"translation", {{"x", translation.x()}, {"y", translation.y()}, {"z", translation.z()}}},
          {"rotation",
           {{"x", rotation.x()}, {"y", rotation.y()}, {"z", rotation.z()}, {"w", rotation.w()}}}};
}

}  // namespace

FrameTransforms::FrameTransforms(const std::string& urdf_path, bool floating_base,
                                 const std::vector<std::string>& joint_names)
    : model_(load(urdf_path, floating_base)),
      data_(model_),
      joints_(Eigen::VectorXd::Zero(model_.n_joints)),
      world_H_frame_(static_cast<std::size_t>(model_.n_frames())) {
  for (const auto& name : joint_names) {
    if (!model_.has_joint(name)) {
      throw std::runtime_error(urdf_path + " has no joint '" + name +
                               "' of the robot's description: give the robot's URDF (--urdf)");
    }
    model_joint_of_.push_back(model_.joint_id(name));
  }
}

std::string FrameTransforms::message(std::uint64_t stamp_ns, std::span<const double> q,
                                     const Eigen::Isometry3d& world_T_base) {
  if (q.size() != model_joint_of_.size()) {
    throw std::invalid_argument(std::to_string(q.size()) + " joint positions for " +
                                std::to_string(model_joint_of_.size()) + " joints");
  }
  for (std::size_t j = 0; j < q.size(); ++j) {
    joints_[model_joint_of_[j]] = q[j];
  }
  const Eigen::Matrix4d world_H_base =
      model_.floating_base ? world_T_base.matrix() : Eigen::Matrix4d::Identity();
  model::forward_kinematics(model_, data_,
                            model::make_configuration(model_, world_H_base, joints_));
  const json timestamp{{"sec", stamp_ns / 1000000000u}, {"nsec", stamp_ns % 1000000000u}};
  json transforms = json::array();
  for (int f = 0; f < model_.n_frames(); ++f) {
    world_H_frame_[f] = model::frame_pose(model_, data_, f);
  }
  for (int f = 0; f < model_.n_frames(); ++f) {
    const int parent = model_.frame_parent[f];
    const std::string& name = model_.frame_name[f];
    if (parent < 0) {
      if (name != "world") {  // a fixed base's URDF may root itself at a "world" link
        transforms.push_back(transform_json(timestamp, "world", name, world_H_frame_[f]));
      }
      continue;
    }
    transforms.push_back(transform_json(timestamp, model_.frame_name[parent], name,
                                        world_H_frame_[parent].inverse() * world_H_frame_[f]));
  }
  return json{{"transforms", std::move(transforms)}}.dump();
}

const std::string& FrameTransforms::schema_name() {
  static const std::string name = "foxglove.FrameTransforms";
  return name;
}

// foxglove.FrameTransforms as a JSON schema (the fields Foxglove reads).
const std::string& FrameTransforms::json_schema() {
  static const std::string schema = [] {
    const json vector3{
        {"type", "object"},
        {"properties",
         {{"x", {{"type", "number"}}}, {"y", {{"type", "number"}}}, {"z", {{"type", "number"}}}}}};
    const json quaternion{{"type", "object"},
                          {"properties",
                           {{"x", {{"type", "number"}}},
                            {"y", {{"type", "number"}}},
                            {"z", {{"type", "number"}}},
                            {"w", {{"type", "number"}}}}}};
    const json time{
        {"type", "object"},
        {"properties", {{"sec", {{"type", "integer"}}}, {"nsec", {{"type", "integer"}}}}}};
    const json transform{{"type", "object"},
                         {"properties",
                          {{"timestamp", time},
                           {"parent_frame_id", {{"type", "string"}}},
                           {"child_frame_id", {{"type", "string"}}},
                           {"translation", vector3},
                           {"rotation", quaternion}}}};
    return json{{"title", "foxglove.FrameTransforms"},
                {"type", "object"},
                {"properties", {{"transforms", {{"type", "array"}, {"items", transform}}}}}}
        .dump();
  }();
  return schema;
}

}  // namespace wbi::bridge
