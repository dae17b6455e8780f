// One robot as the bridge draws it: its description (joint order, URDF) and
// its transforms channel, fed from the raw samples of its state estimate (or
// ground truth) that the bridge already receives, decoded only when a
// transforms message is due and someone subscribes to it.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>

#include "channel_table.hpp"
#include "frame_transforms.hpp"

namespace wbi::bridge {

struct RobotFeedOptions {
  std::string urdf;  // empty: the description's urdf_path
  double transforms_rate_hz = 30.0;
  bool from_ground_truth = false;
};

class RobotFeed {
 public:
  RobotFeed(std::string robot, RobotFeedOptions options, ChannelTable& channels,
            std::uint32_t channel_id);

  const std::string& robot() const { return robot_; }
  std::uint32_t channel_id() const { return channel_id_; }
  // The topic whose samples move the robot (state or ground truth).
  std::string pose_topic() const;

  // A description sample: builds the model once. Returns the error (URDF
  // missing, joints that do not match) for the log, once.
  std::optional<std::string> on_description(std::span<const std::uint8_t> cdr);
  void on_pose_sample(std::uint64_t receive_ns, std::span<const std::uint8_t> cdr);

  // Set once the model is built: the transforms channel can be advertised.
  bool ready() const;
  std::string urdf_path() const;
  std::string urdf_text() const;

 private:
  const std::string robot_;
  const RobotFeedOptions options_;
  ChannelTable& channels_;
  const std::uint32_t channel_id_;
  const std::uint64_t interval_ns_;
  mutable std::mutex mutex_;
  bool described_ = false;
  std::unique_ptr<FrameTransforms> transforms_;
  std::string urdf_path_, urdf_text_;
  std::uint64_t last_sent_ns_ = 0;
};

}  // namespace wbi::bridge
