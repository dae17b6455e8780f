#include "client_publish.hpp"

#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>
#include <wbi/dds/cdr.hpp>
#include <wbi/dds/raw_publisher.hpp>
#include <wbi/dds/topics.hpp>

namespace wbi::bridge {

namespace {

std::vector<std::string> parts_of(const std::string& topic) {
  std::vector<std::string> parts;
  std::stringstream in(topic);
  std::string part;
  while (std::getline(in, part, '/')) {
    parts.push_back(part);
  }
  return parts;
}

// wbi/<robot>/references/<controller>/<input>
bool is_reference_topic(const std::vector<std::string>& parts) {
  return parts.size() == 5 && parts[0] == "wbi" && parts[2] == "references" && !parts[1].empty() &&
         !parts[3].empty() && !parts[4].empty();
}

// wbi/<robot>/commands
bool is_command_topic(const std::vector<std::string>& parts) {
  return parts.size() == 3 && parts[0] == "wbi" && parts[2] == "commands" && !parts[1].empty();
}

bool has_reader(const dds::Participant& participant, const std::string& topic) {
  for (const auto& known : participant.discovered_topics()) {
    if (known.name == topic) {
      return known.readers > 0;
    }
  }
  return false;
}

std::vector<double> numbers(const nlohmann::json& point, const char* key) {
  std::vector<double> out;
  if (!point.contains(key)) {
    return out;
  }
  if (!point[key].is_array()) {
    throw std::invalid_argument(std::string("'") + key + "' must be an array of numbers");
  }
  for (const auto& value : point[key]) {
    if (!value.is_number()) {
      throw std::invalid_argument(std::string("'") + key + "' must be an array of numbers");
    }
    out.push_back(value.get<double>());
  }
  return out;
}

void fill(const std::vector<double>& values, std::vector<double>& out) {
  out.assign(values.begin(), values.end());
}

// A JSON trajectory point as the CDR its controller reads.
std::vector<std::uint8_t> trajectory_point_cdr(std::span<const std::uint8_t> text,
                                               const std::string& robot, std::int64_t default_stamp,
                                               std::uint64_t seq) {
  const auto point = nlohmann::json::parse(text.begin(), text.end(), nullptr, false);
  if (point.is_discarded() || !point.is_object()) {
    throw std::invalid_argument("not a JSON object");
  }
  msg::TrajectoryPoint message;
  message.header().robot(robot);
  message.header().seq(seq);
  message.header().stamp_ns(point.value("stamp_ns", default_stamp));
  message.source("wbi bridge");
  const auto position = numbers(point, "position");
  if (position.empty() || position.size() > msg::MAX_REFERENCE_VALUES) {
    throw std::invalid_argument("'position' must hold 1 to " +
                                std::to_string(msg::MAX_REFERENCE_VALUES) + " numbers");
  }
  fill(position, message.position());
  fill(numbers(point, "velocity"), message.velocity());
  fill(numbers(point, "acceleration"), message.acceleration());
  auto cdr = dds::encode_cdr(message);
  if (cdr.empty()) {
    throw std::invalid_argument("the point could not be serialized");
  }
  return cdr;
}

}  // namespace

struct ClientPublish::Target {
  std::string topic, robot, encoding;
  bool reference = false;
  std::uint64_t seq = 0;
  std::shared_ptr<dds::RawPublisher> writer;
};

ClientPublish::ClientPublish(dds::Participant& participant, bool allow_commands,
                             std::function<std::int64_t(const std::string&)> newest_state_stamp)
    : participant_(participant),
      allow_commands_(allow_commands),
      newest_state_stamp_(std::move(newest_state_stamp)) {}

ClientPublish::~ClientPublish() = default;

std::shared_ptr<dds::RawPublisher> ClientPublish::writer_for(const std::string& topic,
                                                             const std::string& type) {
  if (auto existing = writers_[topic].lock()) {
    return existing;
  }
  auto writer = std::make_shared<dds::RawPublisher>(participant_, topic, type, dds::qos::kCommand);
  writers_[topic] = writer;
  return writer;
}

std::string ClientPublish::advertise(ClientId client, const protocol::ClientChannel& channel,
                                     const std::function<void(const std::string&)>& log) {
  const auto parts = parts_of(channel.topic);
  auto target = std::make_shared<Target>();
  target->topic = channel.topic;
  target->encoding = channel.encoding;
  std::string type;
  if (is_reference_topic(parts)) {
    if (channel.encoding != "cdr" && channel.encoding != "json") {
      return channel.topic + ": encoding '" + channel.encoding + "': a reference takes cdr or json";
    }
    if (!has_reader(participant_, channel.topic)) {
      return channel.topic +
             ": no controller reads this reference input (is it declared, "
             "and its controller hosted?)";
    }
    target->reference = true;
    type = "wbi::msg::TrajectoryPoint";
  } else if (is_command_topic(parts)) {
    if (!allow_commands_) {
      return channel.topic +
             ": raw actuator commands are refused unless the bridge runs with "
             "--allow-commands";
    }
    if (channel.encoding != "cdr") {
      return channel.topic + ": commands are published as cdr";
    }
    type = "wbi::msg::ActuatorCommand";
    log("client " + std::to_string(client) + " publishes raw actuator commands on " +
        channel.topic + " (--allow-commands)");
  } else {
    return channel.topic +
           ": a client may publish only on a controller's reference input "
           "(wbi/<robot>/references/<controller>/<input>)" +
           (allow_commands_ ? " or a robot's commands" : "");
  }
  target->robot = parts[1];
  std::lock_guard lock(mutex_);
  if (channels_.count({client, channel.id}) != 0) {
    return "advertise: channel id " + std::to_string(channel.id) + " is already advertised";
  }
  target->writer = writer_for(channel.topic, type);
  channels_[{client, channel.id}] = std::move(target);
  return {};
}

void ClientPublish::unadvertise(ClientId client, std::uint32_t channel_id) {
  std::lock_guard lock(mutex_);
  channels_.erase({client, channel_id});
}

void ClientPublish::forget(ClientId client) {
  std::lock_guard lock(mutex_);
  std::erase_if(channels_, [client](const auto& entry) { return entry.first.first == client; });
}

std::string ClientPublish::publish(ClientId client, std::uint32_t channel_id,
                                   std::span<const std::uint8_t> payload) {
  std::shared_ptr<Target> target;
  {
    std::lock_guard lock(mutex_);
    const auto found = channels_.find({client, channel_id});
    if (found == channels_.end()) {
      return "message on channel " + std::to_string(channel_id) +
             ", which this client has not advertised (or was refused)";
    }
    target = found->second;
  }
  if (target->encoding == "json") {
    try {
      const auto cdr = trajectory_point_cdr(payload, target->robot,
                                            newest_state_stamp_(target->robot), target->seq++);
      target->writer->publish(cdr);
    } catch (const std::exception& error) {
      return target->topic + ": " + error.what();
    }
    return {};
  }
  if (payload.size() < 4) {
    return target->topic + ": a CDR payload starts with its 4-byte encapsulation header";
  }
  target->writer->publish(payload);
  return {};
}

}  // namespace wbi::bridge
