// Every joint of the project's humanoid (models/humanoid.urdf), in the order
// the balancing deploy files list them: the tests and benchmarks that control it whole.
#pragma once

#include <string>
#include <vector>

namespace wbi::sim_rig {

inline std::vector<std::string> humanoid_joints() {
  return {
      "l_hip_pitch",      "l_hip_roll",       "l_hip_yaw",       "l_knee",         "l_ankle_pitch",
      "l_ankle_roll",     "r_hip_pitch",      "r_hip_roll",      "r_hip_yaw",      "r_knee",
      "r_ankle_pitch",    "r_ankle_roll",     "torso_pitch",     "torso_roll",     "torso_yaw",
      "l_shoulder_pitch", "l_shoulder_roll",  "l_shoulder_yaw",  "l_elbow",        "l_wrist_yaw",
      "l_wrist_pitch",    "r_shoulder_pitch", "r_shoulder_roll", "r_shoulder_yaw", "r_elbow",
      "r_wrist_yaw",      "r_wrist_pitch",    "neck_pitch",      "neck_roll",      "neck_yaw"};
}

}  // namespace wbi::sim_rig
