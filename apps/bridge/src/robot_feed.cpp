#include "robot_feed.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <wbi/dds/cdr.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/msg/eigen.hpp>

namespace wbi::bridge {

namespace {

// A pose whose orientation is not a number is drawn unrotated.
Eigen::Isometry3d isometry(const msg::Pose& pose) {
  Eigen::Isometry3d out = msg::to_isometry(pose);
  if (!out.linear().allFinite()) {
    out.linear().setIdentity();
  }
  return out;
}

}  // namespace

RobotFeed::RobotFeed(std::string robot, RobotFeedOptions options, ChannelTable& channels,
                     std::uint32_t channel_id)
    : robot_(std::move(robot)),
      options_(std::move(options)),
      channels_(channels),
      channel_id_(channel_id),
      interval_ns_(options_.transforms_rate_hz > 0.0
                       ? static_cast<std::uint64_t>(std::llround(1e9 / options_.transforms_rate_hz))
                       : 0) {}

std::string RobotFeed::pose_topic() const {
  return options_.from_ground_truth ? dds::topics::ground_truth(robot_)
                                    : dds::topics::state(robot_);
}

std::optional<std::string> RobotFeed::on_description(std::span<const std::uint8_t> cdr) {
  std::lock_guard lock(mutex_);
  if (described_) {
    return std::nullopt;
  }
  described_ = true;  // one attempt: a description does not change while its robot runs
  msg::RobotDescription description;
  if (!dds::decode_cdr(cdr, description)) {
    return robot_ + ": its description could not be decoded";
  }
  urdf_path_ = options_.urdf.empty() ? description.urdf_path().to_string() : options_.urdf;
  std::ifstream file(urdf_path_);
  if (urdf_path_.empty() || !file) {
    return robot_ + ": no transforms: its URDF '" + urdf_path_ +
           "' is not readable here (give it with --urdf)";
  }
  std::stringstream text;
  text << file.rdbuf();
  std::vector<std::string> joints;
  for (const auto& name : description.joint_names()) {
    joints.push_back(name.to_string());
  }
  try {
    transforms_ =
        std::make_unique<FrameTransforms>(urdf_path_, description.floating_base(), joints);
  } catch (const std::exception& error) {
    return robot_ + ": no transforms: " + error.what();
  }
  urdf_text_ = text.str();
  return std::nullopt;
}

void RobotFeed::on_pose_sample(std::uint64_t receive_ns, std::span<const std::uint8_t> cdr) {
  std::lock_guard lock(mutex_);
  if (!transforms_ || (last_sent_ns_ != 0 && receive_ns - last_sent_ns_ < interval_ns_) ||
      !channels_.has_subscribers(channel_id_)) {
    return;
  }
  std::string message;
  if (options_.from_ground_truth) {
    msg::GroundTruth truth;
    if (!dds::decode_cdr(cdr, truth) || truth.q().size() != transforms_->joint_count()) {
      return;
    }
    message = transforms_->message(receive_ns, truth.q(), isometry(truth.base_pose()));
  } else {
    msg::StateEstimate state;
    if (!dds::decode_cdr(cdr, state) || state.q().size() != transforms_->joint_count()) {
      return;
    }
    message = transforms_->message(receive_ns, state.q(), isometry(state.base_pose()));
  }
  last_sent_ns_ = receive_ns;
  channels_.deliver(
      channel_id_, receive_ns,
      std::span(reinterpret_cast<const std::uint8_t*>(message.data()), message.size()));
}

bool RobotFeed::ready() const {
  std::lock_guard lock(mutex_);
  return transforms_ != nullptr;
}

std::string RobotFeed::urdf_path() const {
  std::lock_guard lock(mutex_);
  return urdf_path_;
}

std::string RobotFeed::urdf_text() const {
  std::lock_guard lock(mutex_);
  return urdf_text_;
}

}  // namespace wbi::bridge
