// `wbi bridge` as a process beside `wbi launch deploy/demo.yaml` (the arm, its
// estimator, model service and PD controller: four processes), reached by a
// WebSocket client in this test: what the Foxglove protocol promises, what a
// client may not do, and what a slow client costs the others.
#include <gtest/gtest.h>

#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>

#include <wbi/dds/cdr.hpp>
#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>

#include "child_process.hpp"
#include "test_support.hpp"
#include "ws_test_client.hpp"

namespace {

using namespace std::chrono_literals;
using nlohmann::json;
using wbi::test::ChildProcess;
using wbi::test::WsTestClient;

// The port of a bridge's "listening on ws://127.0.0.1:PORT" line; 0: none yet.
std::uint16_t listening_port(const std::string& output) {
  const std::string prefix = "listening on ws://127.0.0.1:";
  const auto at = output.find(prefix);
  return at == std::string::npos ? 0
                                 : static_cast<std::uint16_t>(std::strtoul(
                                       output.c_str() + at + prefix.size(), nullptr, 10));
}

std::unique_ptr<ChildProcess> launch;
std::unique_ptr<ChildProcess> bridge;
std::uint16_t port = 0;

class BridgeBesideTheDemo : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto wbi = wbi::test::binary_dir() / "bin" / "wbi";
    launch = std::make_unique<ChildProcess>(
        wbi, std::vector<std::string>{"launch",
                                      (wbi::test::source_dir() / "deploy" / "demo.yaml").string(),
                                      "--duration", "90"});
    ASSERT_TRUE(launch->wait_for_output("[launch] controller: started", 60s)) << launch->output();
    // A small queue per client, so that the slow client's test fills it in a second.
    bridge = std::make_unique<ChildProcess>(
        wbi, std::vector<std::string>{"bridge", "--port", "0", "--client-buffer", "0.5"});
    ASSERT_TRUE(bridge->wait_for_output("transforms of arm on wbi/arm/transforms", 60s))
        << bridge->output();
    const std::string out = bridge->output();
    port = listening_port(out);
    ASSERT_NE(port, 0) << out;
    // The streams the tests read, and the host's latched parameter table,
    // each discovered (the processes' writers appear one by one).
    for (const char* topic : {"wbi/arm/sensors", "wbi/arm/state", "wbi/arm/ground_truth",
                              "wbi/arm/commands", "wbi/arm/controllers/parameters"}) {
      ASSERT_TRUE(bridge->wait_for_output(std::string("channel ") + topic + " ", 30s)) << out;
    }
  }
  static void TearDownTestSuite() {
    if (bridge) {
      EXPECT_EQ(bridge->stop(), 0) << bridge->output();
    }
    bridge.reset();
    launch.reset();
  }

  // A connected client and the channels it was told of, by topic.
  struct Connected {
    std::unique_ptr<WsTestClient> client;
    json server_info;
    std::map<std::string, json> channels;
  };
  static Connected connect() {
    Connected out{std::make_unique<WsTestClient>(port), {}, {}};
    auto info = out.client->next_json("serverInfo", 5s);
    EXPECT_TRUE(info.has_value());
    out.server_info = info.value_or(json());
    auto advertise = out.client->next_json("advertise", 5s);
    EXPECT_TRUE(advertise.has_value());
    const json channels = advertise ? (*advertise)["channels"] : json::array();
    for (const auto& channel : channels) {
      out.channels[channel["topic"]] = channel;
    }
    return out;
  }
};

wbi::msg::SensorSample decode_sensor_sample(const std::string& cdr) {
  wbi::msg::SensorSample sample;
  EXPECT_TRUE(wbi::dds::decode_cdr(
      std::span(reinterpret_cast<const std::uint8_t*>(cdr.data()), cdr.size()), sample));
  return sample;
}

TEST_F(BridgeBesideTheDemo, RefusesAClientWithoutTheFoxgloveSubprotocol) {
  EXPECT_THROW(WsTestClient(port, "chat"), boost::system::system_error);
}

TEST_F(BridgeBesideTheDemo, AdvertisesEveryTopicWithItsIdlSchemaAndTheTransforms) {
  auto connected = connect();
  const auto capabilities = connected.server_info["capabilities"];
  EXPECT_NE(std::find(capabilities.begin(), capabilities.end(), "parameters"), capabilities.end());
  for (const char* topic :
       {"wbi/arm/sensors", "wbi/arm/state", "wbi/arm/ground_truth", "wbi/arm/commands"}) {
    ASSERT_TRUE(connected.channels.count(topic))
        << topic << " not in " << json(connected.channels).dump().substr(0, 3000);
    const auto& channel = connected.channels[topic];
    EXPECT_EQ(channel["encoding"], "cdr") << topic;
    EXPECT_EQ(channel["schemaEncoding"], "omgidl") << topic;
    EXPECT_EQ(channel["schemaName"].get<std::string>().rfind("wbi::msg::", 0), 0u) << topic;
  }
  EXPECT_NE(connected.channels["wbi/arm/sensors"]["schema"].get<std::string>().find(
                "struct SensorSample"),
            std::string::npos);
  ASSERT_TRUE(connected.channels.count("wbi/arm/transforms"));
  EXPECT_EQ(connected.channels["wbi/arm/transforms"]["encoding"], "json");
  EXPECT_EQ(connected.channels["wbi/arm/transforms"]["schemaName"], "foxglove.FrameTransforms");
}

// The bytes are the robot's CDR: decoded here, every sample of the stream in order.
TEST_F(BridgeBesideTheDemo, ForwardsEverySensorSampleAsPublished) {
  auto connected = connect();
  connected.client->send_json(
      {{"op", "subscribe"},
       {"subscriptions",
        {{{"id", 5}, {"channelId", connected.channels["wbi/arm/sensors"]["id"]}}}}});
  std::uint64_t previous_seq = 0;
  std::uint64_t previous_receive = 0;
  int gaps = 0;
  for (int n = 0; n < 500;) {
    const auto frame = connected.client->read(5s);
    ASSERT_TRUE(frame.has_value()) << "after " << n << " samples";
    if (frame->text) {
      ASSERT_NE(frame->json()["op"], "status") << frame->bytes;
      continue;  // advertisements
    }
    ASSERT_EQ(frame->bytes[0], 0x01);
    EXPECT_EQ(frame->subscription(), 5u);
    EXPECT_GE(frame->receive_ns(), previous_receive);
    previous_receive = frame->receive_ns();
    const auto sample = decode_sensor_sample(frame->payload());
    EXPECT_EQ(sample.header().robot().to_string(), "arm");
    EXPECT_EQ(sample.encoder_position().size(), 7u);
    if (n > 0 && sample.header().seq() != previous_seq + 1) {
      ++gaps;
    }
    previous_seq = sample.header().seq();
    ++n;
  }
  EXPECT_EQ(gaps, 0);
}

TEST_F(BridgeBesideTheDemo, KeepsASubscriptionBelowItsMaximumRate) {
  auto connected = connect();
  connected.client->send_json({{"op", "subscribe"},
                               {"subscriptions",
                                {{{"id", 1},
                                  {"channelId", connected.channels["wbi/arm/sensors"]["id"]},
                                  {"maxRateHz", 20}}}}});
  std::vector<std::uint64_t> stamps;
  while (stamps.size() < 11) {
    const auto frame = connected.client->read(2s);
    ASSERT_TRUE(frame.has_value());
    if (!frame->text) {
      stamps.push_back(frame->receive_ns());
    }
  }
  for (std::size_t i = 1; i < stamps.size(); ++i) {
    EXPECT_GE(stamps[i] - stamps[i - 1],
              50'000'000u - 1'000'000u);  // ≤ 20 Hz: ≥ 50 ms apart (1 kHz source)
  }
  EXPECT_LT(stamps.back() - stamps.front(), 10 * 80'000'000u);  // and not much slower
}

// Each bad message gets a status error; the connection keeps serving.
TEST_F(BridgeBesideTheDemo, AnswersMalformedMessagesWithAStatusAndKeepsServing) {
  auto connected = connect();
  auto& client = *connected.client;
  client.send_text("{\"op\": ");
  client.send_json({{"op", "takeOff"}});
  client.send_json({{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", 999999}}}}});
  client.send_text(std::string(2u << 20, ' '));  // over the 1 MiB limit
  client.send_binary({0x01, 0, 0, 0, 0, 42});    // on a channel it never advertised
  client.send_json({{"op", "advertise"},
                    {"channels", {{{"id", 4}, {"topic", "wbi/arm/state"}, {"encoding", "cdr"}}}}});
  std::vector<std::string> errors;
  while (errors.size() < 6) {
    const auto status = client.next_json("status", 5s);
    ASSERT_TRUE(status.has_value()) << errors.size() << " errors so far";
    EXPECT_EQ((*status)["level"], 2) << *status;
    errors.push_back((*status)["message"]);
  }
  EXPECT_NE(errors[0].find("not JSON"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("takeOff"), std::string::npos) << errors[1];
  EXPECT_NE(errors[2].find("999999"), std::string::npos) << errors[2];
  EXPECT_NE(errors[3].find("limit"), std::string::npos) << errors[3];
  EXPECT_NE(errors[4].find("has not advertised"), std::string::npos) << errors[4];
  EXPECT_NE(errors[5].find("reference input"), std::string::npos) << errors[5];
  client.send_json({{"op", "getParameters"}, {"parameterNames", json::array()}, {"id", "alive"}});
  const auto values = client.next_json("parameterValues", 5s);
  ASSERT_TRUE(values.has_value()) << bridge->output();
  EXPECT_EQ((*values)["id"], "alive");
}

json parameter(const json& values, const std::string& name) {
  for (const auto& entry : values["parameters"]) {
    if (entry["name"] == name) {
      return entry;
    }
  }
  return json();
}

TEST_F(BridgeBesideTheDemo, SetsAControllersParameterAndRelaysItsRefusal) {
  auto connected = connect();
  auto& client = *connected.client;
  const std::string gain = "/arm/pd_gravity/gain_scale";
  client.send_json({{"op", "subscribeParameterUpdates"}, {"parameterNames", {gain}}});
  client.send_json({{"op", "setParameters"},
                    {"parameters", {{{"name", gain}, {"value", 0.5}}}},
                    {"id", "set1"}});
  auto reply = client.next_json("parameterValues", 10s);
  ASSERT_TRUE(reply.has_value());
  if (!reply->contains("id")) {  // the update can come first
    reply = client.next_json("parameterValues", 10s);
    ASSERT_TRUE(reply.has_value());
  }
  EXPECT_EQ((*reply)["id"], "set1");
  EXPECT_EQ(parameter(*reply, gain)["value"], 0.5);

  client.send_json({{"op", "setParameters"},
                    {"parameters", {{{"name", gain}, {"value", 100}}}},
                    {"id", "set2"}});
  const auto refusal = client.next_json("status", 10s);
  ASSERT_TRUE(refusal.has_value());
  EXPECT_EQ((*refusal)["level"], 2);
  EXPECT_NE((*refusal)["message"].get<std::string>().find("gain_scale"), std::string::npos)
      << *refusal;
  client.send_json(
      {{"op", "getParameters"}, {"parameterNames", {gain, "/robot_description"}}, {"id", "get"}});
  auto values = client.next_json("parameterValues", 10s);
  while (values && values->value("id", "") != "get") {
    values = client.next_json("parameterValues", 10s);
  }
  ASSERT_TRUE(values.has_value());
  EXPECT_EQ(parameter(*values, gain)["value"], 0.5);  // the refused value was not applied
  EXPECT_NE(parameter(*values, "/robot_description")["value"].get<std::string>().find("<robot"),
            std::string::npos);
  client.send_json({{"op", "setParameters"},
                    {"parameters", {{{"name", gain}, {"value", 1.0}}}},
                    {"id", "back"}});
}

// Foxglove's URDF layer fetches what the URDF names: from its folder only.
TEST_F(BridgeBesideTheDemo, FetchesAssetsFromTheUrdfsFolderOnly) {
  auto connected = connect();
  auto& client = *connected.client;
  client.send_json(
      {{"op", "fetchAsset"}, {"uri", "package://wbi_models/arm7.urdf"}, {"requestId", 11}});
  client.send_json(
      {{"op", "fetchAsset"}, {"uri", "package://wbi_models/../CMakeLists.txt"}, {"requestId", 12}});
  std::map<std::uint32_t, std::string> responses;
  for (int n = 0; n < 50 && responses.size() < 2; ++n) {
    const auto frame = client.read(5s);
    ASSERT_TRUE(frame.has_value());
    if (!frame->text && frame->bytes[0] == 0x04) {
      responses[static_cast<std::uint32_t>(frame->read_le(1, 4))] = frame->bytes;
    }
  }
  ASSERT_EQ(responses.size(), 2u);
  EXPECT_EQ(responses[11][5], 0);  // success
  EXPECT_NE(responses[11].find("<robot"), std::string::npos);
  EXPECT_EQ(responses[12][5], 1);  // refused
  EXPECT_NE(responses[12].find("outside the served folders"), std::string::npos)
      << responses[12].substr(10);
}

TEST_F(BridgeBesideTheDemo, TransformsPlaceEveryLinkThrottledToThirtyHertz) {
  auto connected = connect();
  auto& client = *connected.client;
  client.send_json(
      {{"op", "subscribe"},
       {"subscriptions",
        {{{"id", 3}, {"channelId", connected.channels["wbi/arm/transforms"]["id"]}}}}});
  std::vector<std::uint64_t> stamps;  // the robot's time of each message's pose
  std::set<std::string> children;
  while (stamps.size() < 16) {
    const auto frame = client.read(2s);
    ASSERT_TRUE(frame.has_value());
    if (frame->text) {
      continue;
    }
    const json message = json::parse(frame->payload());
    ASSERT_FALSE(message["transforms"].empty()) << message.dump();
    const auto& time = message["transforms"][0]["timestamp"];
    stamps.push_back(time["sec"].get<std::uint64_t>() * 1'000'000'000u +
                     time["nsec"].get<std::uint64_t>());
    for (const auto& transform : message["transforms"]) {
      children.insert(transform["child_frame_id"]);
    }
  }
  EXPECT_EQ(children.size(), 10u);  // every link of arm7.urdf but its root, "world"
  EXPECT_TRUE(children.count("link_7"));
  // Throttled: of the 1 kHz poses, at most 30 a second of the robot's time
  // (36: a late sample may shift one send). How close to 30 Hz a loaded
  // machine keeps them is a benchmark figure (wbi_bench_bridge,
  // transforms_per_s_per_client), not a check.
  const double seconds = static_cast<double>(stamps.back() - stamps.front()) * 1e-9;
  EXPECT_LT(15.0 / seconds, 36.0) << seconds << " s for 15 intervals";
  std::cout << "transforms: " << 15.0 / seconds << " Hz of robot time\n";
}

// A client that stops reading loses its oldest messages, is told how many,
// and the other client's stream keeps its rate.
TEST_F(BridgeBesideTheDemo, ASlowClientLosesItsOldestMessagesAndSlowsNobody) {
  auto fast = connect();
  const auto sensors = fast.channels["wbi/arm/sensors"]["id"];
  fast.client->send_json(
      {{"op", "subscribe"}, {"subscriptions", {{{"id", 1}, {"channelId", sensors}}}}});
  auto count_for = [&](std::chrono::milliseconds span) {
    int frames = 0;
    const auto end = std::chrono::steady_clock::now() + span;
    while (std::chrono::steady_clock::now() < end) {
      const auto frame = fast.client->read(2s);
      EXPECT_TRUE(frame.has_value());
      if (!frame) {
        break;
      }
      frames += frame->text ? 0 : 1;
    }
    return frames;
  };
  count_for(300ms);  // settle
  const int before = count_for(1000ms);

  auto slow = connect();
  json all = json::array();
  std::uint32_t id = 100;
  for (const auto& [topic, channel] : slow.channels) {
    all.push_back({{"id", id++}, {"channelId", channel["id"]}});
  }
  slow.client->send_json({{"op", "subscribe"}, {"subscriptions", all}});
  const int during = count_for(3000ms) / 3;  // the slow client reads nothing meanwhile
  EXPECT_GE(during, before * 8 / 10)
      << "before " << before << "/s, while another client stalls " << during << "/s";

  std::optional<json> report;
  for (int n = 0; n < 200000 && !report; ++n) {
    const auto frame = slow.client->read(5s);
    ASSERT_TRUE(frame.has_value());
    if (frame->text && frame->json()["op"] == "status" &&
        frame->json()["message"].get<std::string>().find("dropped") != std::string::npos) {
      report = frame->json();
    }
  }
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ((*report)["level"], 1);
  std::cout << "fast client: " << before << " sensor samples/s before, " << during
            << "/s while the other stalled; the slow one was told: " << (*report)["message"]
            << "\n";
}

std::vector<std::uint8_t> service_call(std::uint32_t service, std::uint32_t call,
                                       const json& body) {
  const std::string text = body.dump();
  std::vector<std::uint8_t> frame{0x02};
  for (const std::uint32_t value : {service, call, 4u}) {
    for (int i = 0; i < 4; ++i) {
      frame.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
    }
  }
  frame.insert(frame.end(), {'j', 's', 'o', 'n'});
  frame.insert(frame.end(), text.begin(), text.end());
  return frame;
}

// The response's JSON, or the failure's message prefixed "failure: ".
std::string service_reply(WsTestClient& client, std::uint32_t call) {
  for (int n = 0; n < 20000; ++n) {
    const auto frame = client.read(10s);
    if (!frame) {
      return "no reply";
    }
    if (!frame->text && frame->bytes[0] == 0x03 && frame->read_le(5, 4) == call) {
      return frame->bytes.substr(13 + frame->read_le(9, 4));
    }
    if (frame->text && frame->json()["op"] == "serviceCallFailure" &&
        frame->json()["callId"] == call) {
      return "failure: " + frame->json()["message"].get<std::string>();
    }
  }
  return "no reply";
}

TEST_F(BridgeBesideTheDemo, ListsAndSwitchesTheHostsControllers) {
  auto connected = connect();
  auto& client = *connected.client;
  const auto services = client.next_json("advertiseServices", 10s);
  ASSERT_TRUE(services.has_value()) << bridge->output();
  std::map<std::string, std::uint32_t> ids;
  for (const auto& service : (*services)["services"]) {
    ids[service["name"]] = service["id"];
  }
  ASSERT_TRUE(ids.count("/arm/controllers/list") && ids.count("/arm/controllers/switch"))
      << *services;
  const auto active = [&](std::uint32_t call) {
    client.send_binary(service_call(ids["/arm/controllers/list"], call, json::object()));
    const auto text = service_reply(client, call);
    EXPECT_TRUE(json::accept(text)) << text;
    const auto reply = json::parse(text, nullptr, false);
    std::string name;
    for (const auto& controller : reply["controllers"]) {
      if (controller["active"]) {
        name = controller["name"];
      }
    }
    return name;
  };
  EXPECT_EQ(active(1), "pd_gravity");
  // The host's refusal comes back as the call's failure, with its line.
  client.send_binary(service_call(ids["/arm/controllers/switch"], 2, {{"activate", "hold"}}));
  const auto refusal = service_reply(client, 2);
  EXPECT_NE(refusal.find("failure: /arm/controllers/switch: "), std::string::npos) << refusal;
  EXPECT_NE(refusal.find("deactivate"), std::string::npos) << refusal;
  client.send_binary(service_call(ids["/arm/controllers/switch"], 3,
                                  {{"activate", "hold"}, {"deactivate", "pd_gravity"}}));
  const auto switch_reply = service_reply(client, 3);
  ASSERT_TRUE(json::accept(switch_reply)) << switch_reply;
  EXPECT_NE(json::parse(switch_reply)["result"].get<std::string>().find("hold"), std::string::npos)
      << switch_reply;
  EXPECT_EQ(active(4), "hold");
  client.send_binary(service_call(ids["/arm/controllers/switch"], 5,
                                  {{"activate", "pd_gravity"}, {"deactivate", "hold"}}));
  EXPECT_TRUE(json::accept(service_reply(client, 5)));
  EXPECT_EQ(active(6), "pd_gravity");
}

// A reference input (a reader of wbi/<robot>/references/...: here this
// test's, as a hosted controller's would be) takes JSON points; commands and
// any other topic are refused.
TEST_F(BridgeBesideTheDemo, ClientsPublishOnlyOnReferenceInputs) {
  wbi::dds::Participant participant("test_bridge_references");
  std::mutex mutex;
  std::vector<wbi::msg::TrajectoryPoint> points;
  wbi::dds::Subscriber<wbi::msg::TrajectoryPoint> input(
      participant, "wbi/arm/references/test_controller/posture", wbi::dds::qos::kCommand,
      [&](const wbi::msg::TrajectoryPoint& point, const auto&) {
        std::lock_guard lock(mutex);
        points.push_back(point);
      });
  auto connected = connect();
  auto& client = *connected.client;
  client.send_json({{"op", "advertise"},
                    {"channels",
                     {{{"id", 1},
                       {"topic", "wbi/arm/commands"},
                       {"encoding", "cdr"},
                       {"schemaName", "wbi::msg::ActuatorCommand"}},
                      {{"id", 2},
                       {"topic", "wbi/arm/sensors"},
                       {"encoding", "cdr"},
                       {"schemaName", "wbi::msg::SensorSample"}}}}});
  const auto commands_refused = client.next_json("status", 5s);
  ASSERT_TRUE(commands_refused.has_value());
  EXPECT_NE((*commands_refused)["message"].get<std::string>().find("--allow-commands"),
            std::string::npos)
      << *commands_refused;
  const auto sensors_refused = client.next_json("status", 5s);
  ASSERT_TRUE(sensors_refused.has_value());
  EXPECT_NE((*sensors_refused)["message"].get<std::string>().find("reference input"),
            std::string::npos);
  // The bridge must have discovered the input's reader before it accepts the channel.
  const std::string point = R"({"position": [0.1, 0.2, 0.3], "velocity": [0, 0, 1]})";
  for (int attempt = 0; attempt < 100; ++attempt) {
    client.send_json({{"op", "advertise"},
                      {"channels",
                       {{{"id", 3},
                         {"topic", "wbi/arm/references/test_controller/posture"},
                         {"encoding", "json"},
                         {"schemaName", "wbi::msg::TrajectoryPoint"}}}}});
    client.send_binary([&] {
      std::vector<std::uint8_t> frame{0x01, 3, 0, 0, 0};
      frame.insert(frame.end(), point.begin(), point.end());
      return frame;
    }());
    {
      std::lock_guard lock(mutex);
      if (!points.empty()) {
        break;
      }
    }
    std::this_thread::sleep_for(50ms);  // between tries: the reader's discovery has no event here
    client.send_json({{"op", "unadvertise"}, {"channelIds", {3}}});
  }
  std::lock_guard lock(mutex);
  ASSERT_FALSE(points.empty()) << bridge->output();
  EXPECT_EQ(points[0].position(), (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_EQ(points[0].velocity(), (std::vector<double>{0, 0, 1}));
  EXPECT_EQ(points[0].header().robot().to_string(), "arm");
  EXPECT_GT(points[0].header().stamp_ns(), 0);  // for the robot's newest state
}

// With --allow-commands, raw commands pass, and the bridge names the client.
TEST_F(BridgeBesideTheDemo, RawCommandsPassOnlyWithAllowCommands) {
  ChildProcess permissive(wbi::test::binary_dir() / "bin" / "wbi",
                          {"bridge", "--port", "0", "--allow-commands", "--robot", "ghost"});
  ASSERT_TRUE(permissive.wait_for_output(" (domain ", 30s))
      << permissive.output();  // the whole line
  const auto permissive_port = listening_port(permissive.output());
  ASSERT_NE(permissive_port, 0) << permissive.output();
  wbi::dds::Participant participant("test_bridge_commands");
  std::atomic<int> received{0};
  wbi::dds::Subscriber<wbi::msg::ActuatorCommand> reader(
      participant, "wbi/ghost/commands", wbi::dds::qos::kCommand,
      [&](const wbi::msg::ActuatorCommand&, const auto&) { ++received; });
  WsTestClient client(permissive_port);
  client.send_json({{"op", "advertise"},
                    {"channels",
                     {{{"id", 9},
                       {"topic", "wbi/ghost/commands"},
                       {"encoding", "cdr"},
                       {"schemaName", "wbi::msg::ActuatorCommand"}}}}});
  wbi::msg::ActuatorCommand command;
  command.header().robot("ghost");
  const auto cdr = wbi::dds::encode_cdr(command);
  ASSERT_FALSE(cdr.empty());
  std::vector<std::uint8_t> frame{0x01, 9, 0, 0, 0};
  frame.insert(frame.end(), cdr.begin(), cdr.end());
  for (int n = 0; n < 200 && received == 0; ++n) {
    client.send_binary(frame);  // until the reader is matched: no event tells the client
    std::this_thread::sleep_for(20ms);
  }
  EXPECT_GT(received.load(), 0);
  EXPECT_TRUE(
      permissive.wait_for_output("publishes raw actuator commands on wbi/ghost/commands", 5s))
      << permissive.output();
}

// A topic whose writer goes is unadvertised; when a writer is back, advertised again.
TEST_F(BridgeBesideTheDemo, FollowsTopicsAsTheirWritersComeAndGo) {
  auto connected = connect();
  wbi::dds::Participant participant("test_bridge");
  auto ghost = std::make_unique<wbi::dds::Publisher<wbi::msg::SensorSample>>(
      participant, "wbi/ghost/sensors", wbi::dds::qos::kStream);
  auto advertised = connected.client->next_json("advertise", 10s);
  while (advertised && (*advertised)["channels"][0]["topic"] != "wbi/ghost/sensors") {
    advertised = connected.client->next_json("advertise", 10s);
  }
  ASSERT_TRUE(advertised.has_value()) << bridge->output();
  const auto id = (*advertised)["channels"][0]["id"];
  ghost.reset();
  auto gone = connected.client->next_json("unadvertise", 15s);
  while (gone && std::find((*gone)["channelIds"].begin(), (*gone)["channelIds"].end(), id) ==
                     (*gone)["channelIds"].end()) {
    gone = connected.client->next_json("unadvertise", 15s);  // another test's topic going
  }
  ASSERT_TRUE(gone.has_value());
  ghost = std::make_unique<wbi::dds::Publisher<wbi::msg::SensorSample>>(
      participant, "wbi/ghost/sensors", wbi::dds::qos::kStream);
  auto again = connected.client->next_json("advertise", 15s);
  while (again && (*again)["channels"][0]["topic"] != "wbi/ghost/sensors") {
    again = connected.client->next_json("advertise", 15s);
  }
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ((*again)["channels"][0]["id"], id);  // same topic, same schema: same id
}

}  // namespace
