// The link tree cut at the F/T sensors' fixed joints (wrench_estimator.hpp,
// step 1): which submodel every link belongs to and which submodels each
// sensor joins. Built once, at construction.
#pragma once

#include <string>
#include <vector>

#include "wbi/estimation/wrench_estimator.hpp"

namespace wbi::estimation::detail {

struct Partition {
  std::vector<int> submodel_of_frame;  // [n_frames]
  std::vector<int> sensor_frames;      // [n_sensors] the child link of each sensor joint
  std::vector<Submodel> submodels;     // hypotheses not filled in yet
};

// Appends one line per problem to `errors` (unknown, repeated or movable
// sensor joints); the partition is only meaningful when none was added.
Partition partition_at_sensors(const model::Model& model,
                               const std::vector<ForceTorqueSensor>& sensors,
                               std::vector<std::string>& errors);

}  // namespace wbi::estimation::detail
