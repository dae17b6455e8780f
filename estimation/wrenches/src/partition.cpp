#include "partition.hpp"

#include <set>

namespace wbi::estimation::detail {

namespace {

int sensor_frame(const model::Model& model, const ForceTorqueSensor& sensor,
                 std::vector<std::string>& errors) {
  for (int f = 0; f < model.n_frames(); ++f) {
    if (model.frame_joint[static_cast<std::size_t>(f)] == sensor.joint) {
      if (model.has_joint(sensor.joint)) {
        errors.push_back("F/T sensor '" + sensor.name + "': joint '" + sensor.joint +
                         "' moves; a sensor sits at a fixed joint");
        return -1;
      }
      return f;
    }
  }
  errors.push_back("F/T sensor '" + sensor.name + "': no joint '" + sensor.joint + "' in " +
                   model.source);
  return -1;
}

}  // namespace

Partition partition_at_sensors(const model::Model& model,
                               const std::vector<ForceTorqueSensor>& sensors,
                               std::vector<std::string>& errors) {
  Partition p;
  std::vector<bool> cut(static_cast<std::size_t>(model.n_frames()), false);
  std::set<std::string> names;
  for (const ForceTorqueSensor& sensor : sensors) {
    if (!names.insert(sensor.name).second) {
      errors.push_back("F/T sensor '" + sensor.name + "' is listed twice");
    }
    const int f = sensor_frame(model, sensor, errors);
    p.sensor_frames.push_back(f);
    if (f >= 0) {
      if (cut[static_cast<std::size_t>(f)]) {
        errors.push_back("F/T sensor '" + sensor.name + "': joint '" + sensor.joint +
                         "' already has a sensor");
      }
      cut[static_cast<std::size_t>(f)] = true;
    }
  }
  // Frames come parent first (depth-first), so one pass labels the tree: a
  // link starts a new submodel at the root and behind every cut.
  p.submodel_of_frame.assign(static_cast<std::size_t>(model.n_frames()), -1);
  for (int f = 0; f < model.n_frames(); ++f) {
    const auto uf = static_cast<std::size_t>(f);
    const int parent = model.frame_parent[uf];
    if (parent < 0 || cut[uf]) {
      p.submodel_of_frame[uf] = static_cast<int>(p.submodels.size());
      p.submodels.push_back(Submodel{model.frame_name[uf], {}, {}, {}, {}});
    } else {
      p.submodel_of_frame[uf] = p.submodel_of_frame[static_cast<std::size_t>(parent)];
    }
    p.submodels[static_cast<std::size_t>(p.submodel_of_frame[uf])].links.push_back(
        model.frame_name[uf]);
  }
  for (std::size_t s = 0; s < sensors.size(); ++s) {
    const int f = p.sensor_frames[s];
    if (f < 0) {
      continue;
    }
    const auto uf = static_cast<std::size_t>(f);
    const int child = p.submodel_of_frame[uf];
    const int parent = p.submodel_of_frame[static_cast<std::size_t>(model.frame_parent[uf])];
    p.submodels[static_cast<std::size_t>(child)].child_sensors.push_back(static_cast<int>(s));
    p.submodels[static_cast<std::size_t>(parent)].parent_sensors.push_back(static_cast<int>(s));
  }
  return p;
}

}  // namespace wbi::estimation::detail
