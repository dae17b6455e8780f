// The poses of one robot over time, read from a recording (`wbi record`): the
// robot's description (joint names, base kind, URDF path) and its pose stream,
// the simulator's ground truth (wbi/<robot>/ground_truth) or the estimator's
// state (wbi/<robot>/state). Samples are decoded by the IDL's generated type
// support (Fast CDR), the same code DDS uses.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace wbi::render {

enum class PoseSource { kGroundTruth, kState };

// "ground_truth" or "state"; throws std::invalid_argument for anything else.
PoseSource pose_source_from_name(const std::string& name);
const char* pose_source_name(PoseSource source);

using Vector6d = Eigen::Matrix<double, 6, 1>;

struct PoseFrame {
  double t = 0.0;  // [s] since the first pose of the track (the samples' source stamps)
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();               // world
  Eigen::Quaterniond base_orientation = Eigen::Quaterniond::Identity();  // base in world
  std::vector<double> q;                                                 // joint_names order
  // Ground truth only: per contact link (force, torque about the link origin), world axes.
  std::vector<Vector6d> contact_wrenches;
};

struct PoseTrack {
  std::string robot;
  std::string topic;  // the pose stream read
  std::vector<std::string> joint_names;
  bool floating_base = true;
  std::string urdf_path;            // as the description gives it (informative, may be empty)
  std::int64_t first_stamp_ns = 0;  // source stamp of the first pose (t = 0)
  std::vector<PoseFrame> frames;    // ascending t, at least one

  double duration() const { return frames.back().t; }
  // The last recorded pose at or before t (the first one before it): a frame
  // shows a state the robot was in, never an interpolated one.
  const PoseFrame& at(double t) const;
};

// Reads the description and the pose stream of `robot` ("": the only robot
// with such a stream). Throws std::runtime_error with one line naming the
// file and what is missing (not MCAP, no pose stream, no description, several
// robots and none chosen, joint counts that disagree).
PoseTrack read_pose_track(const std::filesystem::path& file, PoseSource source,
                          const std::string& robot = "");

}  // namespace wbi::render
