#include <wbi/bridge/bridge.hpp>

#include <filesystem>
#include <map>
#include <set>

#include <wbi/dds/topics.hpp>
#include <wbi/recording/topic_subscriptions.hpp>

#include "assets.hpp"
#include "channel_table.hpp"
#include "client_publish.hpp"
#include "controller_hosts.hpp"
#include "protocol.hpp"
#include "robot_feed.hpp"
#include "services.hpp"
#include "websocket_server.hpp"

namespace wbi::bridge {

namespace {

// Channel ids: a DDS topic's is its subscription index + 1; the bridge's own
// channels (transforms) start here.
constexpr std::uint32_t kFirstBridgeChannel = 0x40000000;

// "wbi/<robot>/description" → "<robot>".
std::optional<std::string> robot_of_description(const std::string& topic) {
  const std::string prefix = "wbi/";
  const std::string suffix = "/description";
  if (topic.size() <= prefix.size() + suffix.size() || topic.rfind(prefix, 0) != 0 ||
      topic.compare(topic.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return std::nullopt;
  }
  const std::string robot =
      topic.substr(prefix.size(), topic.size() - prefix.size() - suffix.size());
  if (robot.find('/') != std::string::npos) {
    return std::nullopt;
  }
  return robot;
}

std::string drop_report(const std::map<std::uint32_t, std::uint64_t>& drops,
                        const ChannelTable& channels) {
  std::uint64_t total = 0;
  std::string per_channel;
  for (const auto& [id, count] : drops) {
    total += count;
    per_channel += per_channel.empty() ? "" : ", ";
    per_channel +=
        channels.topic_of(id).value_or(std::to_string(id)) + ": " + std::to_string(count);
  }
  return "slow connection: " + std::to_string(total) +
         " messages dropped in the last second, the oldest first (" + per_channel + ")";
}

}  // namespace

struct Bridge::Impl {
  Impl(dds::Participant& participant_, BridgeOptions options_, Log log_);
  ~Impl();

  void opened(ClientId client, const std::string& peer);
  void closed(ClientId client);
  void text(ClientId client, const std::string& text);
  void handle(ClientId client, const protocol::Subscribe& request);
  void handle(ClientId client, const protocol::Unsubscribe& request);
  void handle(ClientId client, const protocol::GetParameters& request);
  void handle(ClientId client, const protocol::SetParameters& request);
  void handle(ClientId client, const protocol::SubscribeParameterUpdates& request);
  void handle(ClientId client, const protocol::UnsubscribeParameterUpdates& request);
  void handle(ClientId client, const protocol::FetchAsset& request);
  void handle(ClientId client, const protocol::ClientAdvertise& request);
  void handle(ClientId client, const protocol::ClientUnadvertise& request);
  void handle(ClientId client, const protocol::Unsupported& request);
  void binary(ClientId client, std::span<const std::uint8_t> frame);
  void parameters_changed(const std::vector<protocol::Parameter>& changed);
  void report_drops();
  void on_sample(std::uint32_t index, const recording::RecordedTopic& topic, std::uint64_t log_time,
                 std::uint64_t publish_time, std::span<const std::uint8_t> cdr);
  std::int64_t newest_state_stamp(const std::string& robot);
  void follow_hosts();
  // A topic's reader is held while someone wants it (counted): a subscribed
  // channel, a subscribed robot's transforms, a robot's description.
  void want(const std::string& topic, bool wanted);
  void channel_demand(std::uint32_t channel, bool wanted);
  void add_robots();
  void follow_robots();
  void follow_topics();
  void status(ClientId client, protocol::StatusLevel level, const std::string& message);
  void broadcast(const std::string& json);

  dds::Participant& participant;
  BridgeOptions options;
  Log log;
  ChannelTable channels;
  AssetFolders assets;
  std::unique_ptr<ControllerHosts> parameters;
  std::unique_ptr<WebSocketServer> server;
  std::unique_ptr<Services> services;
  std::unique_ptr<ClientPublish> publish;
  std::unique_ptr<recording::TopicSubscriptions> subscriptions;

  std::mutex robots_mutex;  // robots is read on DDS threads
  std::map<std::string, std::unique_ptr<RobotFeed>> robots;
  std::map<std::string, RobotFeed*> robot_by_topic;  // description and pose topics
  std::set<std::string> robots_announced;
  std::map<std::string, std::int64_t> state_stamps;  // newest Header.stamp_ns of each robot's state

  std::mutex clients_mutex;
  // Per client, the parameters it follows (an empty set with the flag: all).
  struct ParameterFollow {
    bool all = false;
    std::set<std::string> names;
  };
  std::map<ClientId, ParameterFollow> parameter_follows;
  std::set<ClientId> clients;

  std::mutex wants_mutex;
  std::map<std::string, int> wants;                // by topic
  std::map<std::string, std::size_t> topic_index;  // in subscriptions, once discovered
  std::set<std::string> state_followed;            // robots whose state stamps JSON references
};

Bridge::Impl::Impl(dds::Participant& participant_, BridgeOptions options_, Log log_)
    : participant(participant_),
      options(std::move(options_)),
      log(std::move(log_)),
      channels([this](std::uint32_t channel, bool wanted) { channel_demand(channel, wanted); }) {
  for (const auto& path : options.mesh_paths) {
    assets.add(path);
  }
  parameters = std::make_unique<ControllerHosts>(
      participant.options(), options.call_timeout,
      [this](const std::vector<protocol::Parameter>& changed) { parameters_changed(changed); });
  ServerOptions server_options;
  server_options.address = options.address;
  server_options.port = options.port;
  server_options.client_queue_bytes = options.client_queue_bytes;
  server_options.max_client_message_bytes = options.max_client_message_bytes;
  server = std::make_unique<WebSocketServer>(
      server_options,
      ServerHandlers{
          [this](ClientId client, const std::string& peer) { opened(client, peer); },
          [this](ClientId client, const std::string& message) { text(client, message); },
          [this](ClientId client, std::span<const std::uint8_t> frame) { binary(client, frame); },
          [this](ClientId client) { closed(client); }});
  channels.attach(server.get());
  services = std::make_unique<Services>(*parameters, *server);
  publish = std::make_unique<ClientPublish>(
      participant, options.allow_commands,
      [this](const std::string& robot) { return newest_state_stamp(robot); });
  server->every(std::chrono::milliseconds(1000), [this] { report_drops(); });
  subscriptions = std::make_unique<recording::TopicSubscriptions>(
      participant, [](const std::string&) { return true; },
      [this](std::uint32_t index, const recording::RecordedTopic& topic, std::uint64_t log_time,
             std::uint64_t publish_time, std::span<const std::uint8_t> cdr) {
        on_sample(index, topic, log_time, publish_time, cdr);
      },
      [this](const std::string& line) {
        // TopicSubscriptions speaks as the recorder it was written for.
        log(line.rfind("recording ", 0) == 0 ? "channel " + line.substr(10) : line);
      },
      recording::TopicSubscriptions::Readers::on_demand);
}

Bridge::Impl::~Impl() {
  subscriptions->unsubscribe_all();  // no DDS callback after this
  publish.reset();
  parameters.reset();  // its worker ends: no service call after this
  services.reset();
  channels.attach(nullptr);
  server.reset();
}

void Bridge::Impl::status(ClientId client, protocol::StatusLevel level,
                          const std::string& message) {
  server->send(client, OutgoingMessage::json(protocol::status(level, message)));
}

void Bridge::Impl::broadcast(const std::string& json) {
  std::lock_guard lock(clients_mutex);
  for (const auto client : clients) {
    server->send(client, OutgoingMessage::json(json));
  }
}

void Bridge::Impl::opened(ClientId client, const std::string& peer) {
  log("client " + std::to_string(client) + " connected from " + peer);
  server->send(client,
               OutgoingMessage::json(protocol::server_info(
                   "wbi bridge",
                   {"parameters", "parametersSubscribe", "assets", "clientPublish", "services"},
                   {"cdr", "json"}, std::to_string(participant.info().start_ns))));
  {
    std::lock_guard lock(clients_mutex);
    clients.insert(client);
  }
  const auto advertised = channels.advertised();
  server->send(client, OutgoingMessage::json(protocol::advertise(advertised)));
  if (const auto offered = services->all(); !offered.empty()) {
    server->send(client, OutgoingMessage::json(protocol::advertise_services(offered)));
  }
}

void Bridge::Impl::closed(ClientId client) {
  channels.forget(client);
  publish->forget(client);
  {
    std::lock_guard lock(clients_mutex);
    clients.erase(client);
    parameter_follows.erase(client);
  }
  log("client " + std::to_string(client) + " disconnected");
}

void Bridge::Impl::text(ClientId client, const std::string& message) {
  try {
    std::visit([&](const auto& request) { handle(client, request); },
               protocol::parse_client_text(message));
  } catch (const protocol::ProtocolError& error) {
    status(client, protocol::StatusLevel::error, error.what());
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::Subscribe& request) {
  for (const auto& subscription : request.subscriptions) {
    if (const auto refused = channels.subscribe(client, subscription)) {
      status(client, protocol::StatusLevel::error, *refused);
    }
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::Unsubscribe& request) {
  for (const auto id : request.subscription_ids) {
    if (!channels.unsubscribe(client, id)) {
      status(client, protocol::StatusLevel::warning,
             "unsubscribe: no subscription " + std::to_string(id));
    }
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::GetParameters& request) {
  std::vector<std::string> unknown;
  const auto values = parameters->get(request.names, &unknown);
  server->send(client, OutgoingMessage::json(protocol::parameter_values(values, request.id)));
  for (const auto& name : unknown) {
    status(client, protocol::StatusLevel::warning, "getParameters: no parameter " + name);
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::SetParameters& request) {
  std::vector<std::string> names;
  for (const auto& parameter : request.parameters) {
    names.push_back(parameter.name);
  }
  parameters->set(request.parameters, [this, client, names, id = request.id](
                                          std::vector<protocol::Parameter> applied,
                                          std::vector<std::string> refusals) {
    for (const auto& refusal : refusals) {
      status(client, protocol::StatusLevel::error, "setParameters: " + refusal);
    }
    // The values now: those applied (the host's table may not have caught up), else the table's.
    auto values = parameters->get(names, nullptr);
    for (auto& value : values) {
      for (const auto& set : applied) {
        if (set.name == value.name) {
          value = set;
        }
      }
    }
    server->send(client, OutgoingMessage::json(protocol::parameter_values(values, id)));
  });
}

void Bridge::Impl::handle(ClientId client, const protocol::SubscribeParameterUpdates& request) {
  std::lock_guard lock(clients_mutex);
  auto& follow = parameter_follows[client];
  follow.all = follow.all || request.names.empty();
  follow.names.insert(request.names.begin(), request.names.end());
}

void Bridge::Impl::handle(ClientId client, const protocol::UnsubscribeParameterUpdates& request) {
  std::lock_guard lock(clients_mutex);
  if (request.names.empty()) {
    parameter_follows.erase(client);
    return;
  }
  auto& follow = parameter_follows[client];
  for (const auto& name : request.names) {
    follow.names.erase(name);
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::FetchAsset& request) {
  try {
    const auto bytes = assets.read(request.uri);
    server->send(client, OutgoingMessage::binary(protocol::fetch_asset_response(
                             request.request_id, std::nullopt, bytes)));
  } catch (const std::exception& error) {
    server->send(client, OutgoingMessage::binary(
                             protocol::fetch_asset_response(request.request_id, error.what(), {})));
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::ClientAdvertise& request) {
  for (const auto& channel : request.channels) {
    if (const auto refusal = publish->advertise(client, channel, log); !refusal.empty()) {
      status(client, protocol::StatusLevel::error, "advertise: " + refusal);
    } else if (channel.encoding == "json") {
      // A JSON point without a stamp is for the robot's newest state: follow it.
      const std::string robot = channel.topic.substr(4, channel.topic.find('/', 4) - 4);
      bool first = false;
      {
        std::lock_guard lock(wants_mutex);
        first = state_followed.insert(robot).second;
      }
      if (first) {
        want(dds::topics::state(robot), true);
      }
    }
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::ClientUnadvertise& request) {
  for (const auto id : request.channel_ids) {
    publish->unadvertise(client, id);
  }
}

void Bridge::Impl::handle(ClientId client, const protocol::Unsupported& request) {
  status(client, protocol::StatusLevel::error,
         "'" + request.op + "' is not offered by this bridge (no connection graph)");
}

void Bridge::Impl::binary(ClientId client, std::span<const std::uint8_t> frame) {
  try {
    const auto message = protocol::parse_client_binary(frame);
    if (const auto* data = std::get_if<protocol::ClientMessageData>(&message)) {
      if (const auto refusal = publish->publish(client, data->channel_id, data->payload);
          !refusal.empty()) {
        status(client, protocol::StatusLevel::error, refusal);
      }
    } else {
      services->call(client, std::get<protocol::ServiceCallRequest>(message));
    }
  } catch (const protocol::ProtocolError& error) {
    status(client, protocol::StatusLevel::error, error.what());
  }
}

void Bridge::Impl::parameters_changed(const std::vector<protocol::Parameter>& changed) {
  std::lock_guard lock(clients_mutex);
  for (const auto& [client, follow] : parameter_follows) {
    std::vector<protocol::Parameter> wanted;
    for (const auto& parameter : changed) {
      if (follow.all || follow.names.count(parameter.name) != 0) {
        wanted.push_back(parameter);
      }
    }
    if (!wanted.empty()) {
      server->send(client, OutgoingMessage::json(protocol::parameter_values(wanted, "")));
    }
  }
}

void Bridge::Impl::report_drops() {
  std::vector<ClientId> now;
  {
    std::lock_guard lock(clients_mutex);
    now.assign(clients.begin(), clients.end());
  }
  for (const auto client : now) {
    const auto drops = server->take_drops(client);
    if (!drops.empty()) {
      status(client, protocol::StatusLevel::warning, drop_report(drops, channels));
    }
  }
}

void Bridge::Impl::on_sample(std::uint32_t index, const recording::RecordedTopic& topic,
                             std::uint64_t log_time, std::uint64_t publish_time,
                             std::span<const std::uint8_t> cdr) {
  channels.deliver(index + 1, log_time, cdr);
  RobotFeed* robot = nullptr;
  {
    std::lock_guard lock(robots_mutex);
    const auto found = robot_by_topic.find(topic.topic.name);
    if (found == robot_by_topic.end()) {
      return;
    }
    robot = found->second;
    if (topic.topic.name == dds::topics::state(robot->robot())) {
      state_stamps[robot->robot()] = static_cast<std::int64_t>(publish_time);
    }
  }
  if (topic.topic.name == dds::topics::description(robot->robot())) {
    if (const auto problem = robot->on_description(cdr)) {
      log("warning: " + *problem);
    }
  } else if (topic.topic.name == robot->pose_topic()) {
    robot->on_pose_sample(log_time, cdr);
  }
}

void Bridge::Impl::want(const std::string& topic, bool wanted) {
  std::lock_guard lock(wants_mutex);
  const int count = (wants[topic] += wanted ? 1 : -1);
  const auto index = topic_index.find(topic);
  if (index == topic_index.end()) {
    return;  // opened when discovered
  }
  if (wanted && count == 1) {
    subscriptions->open(index->second);
  } else if (!wanted && count == 0) {
    subscriptions->close(index->second);
  }
}

void Bridge::Impl::channel_demand(std::uint32_t channel, bool wanted) {
  if (channel < kFirstBridgeChannel) {
    want((*subscriptions)[channel - 1].topic.name, wanted);
    return;
  }
  std::string pose_topic;
  {
    std::lock_guard lock(robots_mutex);
    for (const auto& [name, feed] : robots) {
      if (feed->channel_id() == channel) {
        pose_topic = feed->pose_topic();
      }
    }
  }
  if (!pose_topic.empty()) {
    want(pose_topic, wanted);
  }
}

std::int64_t Bridge::Impl::newest_state_stamp(const std::string& robot) {
  std::lock_guard lock(robots_mutex);
  const auto found = state_stamps.find(robot);
  return found == state_stamps.end() ? 0 : found->second;
}

// A robot whose controller host answers on the domain gets its services.
void Bridge::Impl::follow_hosts() {
  std::vector<std::string> names;
  {
    std::lock_guard lock(robots_mutex);
    for (const auto& [name, feed] : robots) {
      names.push_back(name);
    }
  }
  for (const auto& topic : participant.discovered_topics()) {
    for (const auto& robot : names) {
      if (topic.name == dds::topics::controller_service(robot) + "/request" && topic.readers > 0) {
        if (const auto added = services->add_robot(robot); !added.empty()) {
          broadcast(protocol::advertise_services(added));
          log("services of " + robot + "'s controller host: " + added[0].name + ", " +
              added[1].name);
        }
      }
    }
  }
}

// Robots come before their topics' readers, so that a latched description
// arriving with its reader finds its robot.
void Bridge::Impl::add_robots() {
  for (const auto& topic : participant.discovered_topics()) {
    const auto robot = robot_of_description(topic.name);
    if (!robot || (!options.robot.empty() && *robot != options.robot)) {
      continue;
    }
    {
      std::lock_guard lock(robots_mutex);
      if (robots.count(*robot) != 0) {
        continue;
      }
      const auto id = kFirstBridgeChannel + static_cast<std::uint32_t>(robots.size());
      auto feed =
          std::make_unique<RobotFeed>(*robot,
                                      RobotFeedOptions{options.urdf, options.transforms_rate_hz,
                                                       options.transforms_from_ground_truth},
                                      channels, id);
      robot_by_topic[topic.name] = feed.get();
      robot_by_topic[feed->pose_topic()] = feed.get();
      robot_by_topic[dds::topics::state(*robot)] = feed.get();
      robots[*robot] = std::move(feed);
    }
    // Outside robots_mutex: a reader's close waits for its callbacks, which take it.
    parameters->add_robot(*robot);
    want(topic.name, true);  // the description, for the model: held for the bridge's life
  }
}

// A robot whose model is built gets its transforms channel and robot_description.
void Bridge::Impl::follow_robots() {
  std::vector<RobotFeed*> ready;
  {
    std::lock_guard lock(robots_mutex);
    for (auto& [name, feed] : robots) {
      if (feed->ready() && robots_announced.insert(name).second) {
        ready.push_back(feed.get());
      }
    }
  }
  for (auto* feed : ready) {
    parameters->set_robot_description(feed->robot(), feed->urdf_text());
    assets.add(std::filesystem::path(feed->urdf_path()).parent_path());
    protocol::Channel channel{feed->channel_id(),
                              "wbi/" + feed->robot() + "/transforms",
                              "json",
                              FrameTransforms::schema_name(),
                              FrameTransforms::json_schema(),
                              "jsonschema"};
    channels.add(channel);
    channels.set_advertised(channel.id, true);
    broadcast(protocol::advertise(std::vector{channel}));
    log("transforms of " + feed->robot() + " on " + channel.topic + " (URDF " + feed->urdf_path() +
        ")");
  }
}

// Topics with a writer are advertised; one that lost its last writer is
// unadvertised, and advertised again (same id) when a writer comes back.
void Bridge::Impl::follow_topics() {
  const auto added_from = subscriptions->size();
  subscriptions->discover();
  for (std::size_t index = added_from; index < subscriptions->size(); ++index) {
    const auto& recorded = (*subscriptions)[index];
    {
      std::lock_guard lock(wants_mutex);
      topic_index[recorded.topic.name] = index;
      if (wants[recorded.topic.name] > 0) {
        subscriptions->open(index);
      }
    }
    if (recorded.idl_text.empty()) {
      continue;  // no schema a client could decode it with
    }
    channels.add({static_cast<std::uint32_t>(index + 1), recorded.topic.name, "cdr",
                  recorded.topic.type, recorded.idl_text, "omgidl"});
  }
  std::set<std::string> written;
  for (const auto& topic : participant.discovered_topics()) {
    if (topic.writers > 0) {
      written.insert(topic.name);
    }
  }
  std::vector<protocol::Channel> appeared;
  std::vector<std::uint32_t> gone;
  for (std::size_t index = 0; index < subscriptions->size(); ++index) {
    const auto& recorded = (*subscriptions)[index];
    const auto id = static_cast<std::uint32_t>(index + 1);
    if (recorded.idl_text.empty()) {
      continue;
    }
    const bool alive = written.count(recorded.topic.name) != 0;
    if (channels.set_advertised(id, alive)) {
      if (alive) {
        appeared.push_back(
            {id, recorded.topic.name, "cdr", recorded.topic.type, recorded.idl_text, "omgidl"});
      } else {
        gone.push_back(id);
      }
    }
  }
  if (!appeared.empty()) {
    broadcast(protocol::advertise(appeared));
  }
  if (!gone.empty()) {
    broadcast(protocol::unadvertise(gone));
  }
}

Bridge::Bridge(dds::Participant& participant, BridgeOptions options, Log log)
    : impl_(std::make_unique<Impl>(participant, std::move(options), std::move(log))) {}

Bridge::~Bridge() = default;

std::uint16_t Bridge::port() const { return impl_->server->port(); }

void Bridge::discover() {
  impl_->add_robots();
  impl_->follow_topics();
  impl_->follow_robots();
  impl_->follow_hosts();
}

BridgeCounts Bridge::counts() const {
  BridgeCounts counts;
  counts.clients = impl_->server->client_count();
  counts.channels = impl_->channels.advertised().size();
  counts.forwarded = impl_->channels.forwarded();
  return counts;
}

}  // namespace wbi::bridge
