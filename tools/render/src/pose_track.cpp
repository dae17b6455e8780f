// Reading a robot's poses from an MCAP recording (pose_track.hpp).
#include "wbi/render/pose_track.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <stdexcept>

#include <wbi/dds/cdr.hpp>
#include <wbi/mcap/reader.hpp>
#include <wbi/msg/eigen.hpp>

namespace wbi::render {

namespace {

constexpr const char* kDescriptionType = "wbi::msg::RobotDescription";
constexpr double kNsPerSecond = 1e9;

const char* stream_type(PoseSource source) {
  return source == PoseSource::kGroundTruth ? "wbi::msg::GroundTruth" : "wbi::msg::StateEstimate";
}

// The robot of a topic "wbi/<robot>/<leaf>", or "" when it is not one.
std::string robot_of(const std::string& topic, const std::string& leaf) {
  const std::string prefix = "wbi/";
  const std::string suffix = "/" + leaf;
  if (topic.size() <= prefix.size() + suffix.size() || topic.rfind(prefix, 0) != 0 ||
      topic.compare(topic.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return "";
  }
  return topic.substr(prefix.size(), topic.size() - prefix.size() - suffix.size());
}

PoseFrame to_frame(const msg::Pose& pose, const std::vector<double>& q) {
  PoseFrame f;
  f.base_position = msg::to_eigen(pose.position());
  f.base_orientation = msg::to_eigen(pose.orientation());
  if (f.base_orientation.norm() < 1e-9) {
    f.base_orientation = Eigen::Quaterniond::Identity();  // a fixed-base robot may send zeros
  }
  f.base_orientation.normalize();
  f.q = q;
  return f;
}

}  // namespace

PoseSource pose_source_from_name(const std::string& name) {
  if (name == "ground_truth") {
    return PoseSource::kGroundTruth;
  }
  if (name == "state") {
    return PoseSource::kState;
  }
  throw std::invalid_argument("--source: '" + name + "' is not ground_truth or state");
}

const char* pose_source_name(PoseSource source) {
  return source == PoseSource::kGroundTruth ? "ground_truth" : "state";
}

const PoseFrame& PoseTrack::at(double t) const {
  const auto after = std::upper_bound(frames.begin(), frames.end(), t,
                                      [](double v, const PoseFrame& f) { return v < f.t; });
  return after == frames.begin() ? frames.front() : *(after - 1);
}

PoseTrack read_pose_track(const std::filesystem::path& file, PoseSource source,
                          const std::string& robot) {
  const std::string where = file.string();
  const mcap::Reader reader(file);
  const auto& info = reader.info();
  const std::string leaf = source == PoseSource::kGroundTruth ? "ground_truth" : "state";

  // The pose stream: a channel of the stream's type named wbi/<robot>/<leaf>.
  std::map<std::string, std::uint16_t> streams;  // robot -> channel id
  for (const auto& [id, channel] : info.channels) {
    const auto schema = info.schemas.find(channel.schema_id);
    const std::string r = robot_of(channel.topic, leaf);
    if (schema != info.schemas.end() && schema->second.name == stream_type(source) && !r.empty() &&
        (robot.empty() || r == robot)) {
      streams[r] = id;
    }
  }
  if (streams.empty()) {
    throw std::runtime_error(where + ": no " + leaf + " stream (" + stream_type(source) +
                             " on wbi/" + (robot.empty() ? "<robot>" : robot) + "/" + leaf +
                             ") in the recording");
  }
  if (streams.size() > 1) {
    std::string names;
    for (const auto& [r, id] : streams) {
      names += (names.empty() ? "" : ", ") + r;
    }
    throw std::runtime_error(where + ": several robots (" + names + "): choose one with --robot");
  }
  PoseTrack track;
  track.robot = streams.begin()->first;
  track.topic = "wbi/" + track.robot + "/" + leaf;
  const std::uint16_t stream_id = streams.begin()->second;
  const std::string description_topic = "wbi/" + track.robot + "/description";

  msg::RobotDescription description;
  msg::GroundTruth truth;
  msg::StateEstimate state;
  bool have_description = false;
  std::optional<std::int64_t> first_stamp;
  std::size_t undecodable = 0;

  auto cursor = reader.messages(mcap::Order::log_time);
  while (const auto* m = cursor.next()) {
    if (m->channel->topic == description_topic && m->schema != nullptr &&
        m->schema->name == kDescriptionType) {
      if (!have_description && dds::decode_cdr(m->data, description)) {
        have_description = true;
      }
      continue;
    }
    if (m->channel->id != stream_id) {
      continue;
    }
    PoseFrame frame;
    std::int64_t stamp = 0;
    if (source == PoseSource::kGroundTruth) {
      if (!dds::decode_cdr(m->data, truth)) {
        ++undecodable;
        continue;
      }
      frame = to_frame(truth.base_pose(), truth.q());
      for (const auto& w : truth.contact_wrenches()) {
        msg::to_eigen(w, frame.contact_wrenches.emplace_back());
      }
      stamp = truth.header().stamp_ns();
    } else {
      if (!dds::decode_cdr(m->data, state)) {
        ++undecodable;
        continue;
      }
      frame = to_frame(state.base_pose(), state.q());
      stamp = state.header().stamp_ns();
    }
    if (!first_stamp) {
      first_stamp = stamp;
    }
    frame.t = static_cast<double>(stamp - *first_stamp) / kNsPerSecond;
    track.frames.push_back(std::move(frame));
  }
  if (track.frames.empty()) {
    throw std::runtime_error(
        where + ": " + track.topic + " holds no decodable sample" +
        (undecodable > 0 ? " (" + std::to_string(undecodable) + " undecodable)" : ""));
  }
  if (!have_description) {
    throw std::runtime_error(where + ": no robot description (" + description_topic +
                             ") in the recording: start `wbi record` before or with the robot");
  }
  // Source stamps may arrive out of log-time order (several writers); the
  // track is in source time.
  std::stable_sort(track.frames.begin(), track.frames.end(),
                   [](const PoseFrame& a, const PoseFrame& b) { return a.t < b.t; });
  const double t0 = track.frames.front().t;
  for (auto& f : track.frames) {
    f.t -= t0;
  }
  track.first_stamp_ns = *first_stamp + static_cast<std::int64_t>(std::llround(t0 * kNsPerSecond));
  for (const auto& name : description.joint_names()) {
    track.joint_names.emplace_back(name.to_string());
  }
  track.floating_base = description.floating_base();
  track.urdf_path = description.urdf_path().to_string();
  for (const auto& f : track.frames) {
    if (f.q.size() != track.joint_names.size()) {
      throw std::runtime_error(where + ": " + track.topic + " has " + std::to_string(f.q.size()) +
                               " joint positions, the description " +
                               std::to_string(track.joint_names.size()) + " joints");
    }
  }
  return track;
}

}  // namespace wbi::render
