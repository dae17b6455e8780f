// The bridge's parts without sockets or DDS: the Foxglove protocol's messages
// as bytes, a client's bounded queue, the served asset folders and the
// transforms of the project's arm.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include <wbi/model/kinematics.hpp>
#include <wbi/model/urdf.hpp>

#include "assets.hpp"
#include "frame_transforms.hpp"
#include "protocol.hpp"
#include "send_queue.hpp"
#include "test_support.hpp"

namespace {

using nlohmann::json;
using namespace wbi::bridge;

std::uint64_t read_le(const std::uint8_t* at, int bytes) {
  std::uint64_t value = 0;
  for (int i = 0; i < bytes; ++i) {
    value |= static_cast<std::uint64_t>(at[i]) << (8 * i);
  }
  return value;
}

TEST(BridgeProtocol, MessageDataHeaderIsOpcodeThenLittleEndianIdAndTime) {
  const auto header = protocol::message_data_header(0x01020304u, 0x1122334455667788ull);
  EXPECT_EQ(header[0], 0x01);
  EXPECT_EQ(read_le(&header[1], 4), 0x01020304u);
  EXPECT_EQ(read_le(&header[5], 8), 0x1122334455667788ull);
}

TEST(BridgeProtocol, FetchAssetResponseCarriesDataOrError) {
  const std::vector<std::uint8_t> data{1, 2, 3};
  const auto ok = protocol::fetch_asset_response(9, std::nullopt, data);
  ASSERT_EQ(ok.size(), 1u + 4 + 1 + 4 + 3);
  EXPECT_EQ(ok[0], 0x04);
  EXPECT_EQ(read_le(&ok[1], 4), 9u);
  EXPECT_EQ(ok[5], 0);
  EXPECT_EQ(read_le(&ok[6], 4), 0u);
  EXPECT_EQ(ok.back(), 3);
  const auto failed = protocol::fetch_asset_response(9, std::string("gone"), data);
  ASSERT_EQ(failed.size(), 1u + 4 + 1 + 4 + 4);
  EXPECT_EQ(failed[5], 1);
  EXPECT_EQ(std::string(failed.begin() + 10, failed.end()), "gone");
}

TEST(BridgeProtocol, ServerMessagesAreTheSpecsJson) {
  const protocol::Channel channel{
      3, "wbi/arm/sensors", "cdr", "wbi::msg::SensorSample", "struct X {};", "omgidl"};
  const auto advertise = json::parse(protocol::advertise(std::vector{channel}));
  EXPECT_EQ(advertise["op"], "advertise");
  EXPECT_EQ(advertise["channels"][0]["id"], 3);
  EXPECT_EQ(advertise["channels"][0]["schemaEncoding"], "omgidl");
  EXPECT_EQ(advertise["channels"][0]["schemaName"], "wbi::msg::SensorSample");
  const auto status = json::parse(protocol::status(protocol::StatusLevel::warning, "slow"));
  EXPECT_EQ(status["level"], 1);
  const std::vector<protocol::Parameter> parameters{{"/arm/pd/gain_scale", 0.5},
                                                    {"/arm/pd/target", std::vector<double>{1, 2}},
                                                    {"/x", std::string("t")}};
  const auto values = json::parse(protocol::parameter_values(parameters, "r1"));
  EXPECT_EQ(values["id"], "r1");
  EXPECT_EQ(values["parameters"][0]["type"], "float64");
  EXPECT_EQ(values["parameters"][1]["type"], "float64_array");
  EXPECT_EQ(values["parameters"][1]["value"][1], 2.0);
  EXPECT_FALSE(values["parameters"][2].contains("type"));
  EXPECT_FALSE(json::parse(protocol::parameter_values(parameters, ""))
                   .contains("id"));  // an update nobody asked for
}

TEST(BridgeProtocol, ParsesTheClientRequests) {
  const auto subscribe = std::get<protocol::Subscribe>(protocol::parse_client_text(
      R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":4},{"id":2,"channelId":5,"maxRateHz":30}]})"));
  ASSERT_EQ(subscribe.subscriptions.size(), 2u);
  EXPECT_EQ(subscribe.subscriptions[0].channel_id, 4u);
  EXPECT_EQ(subscribe.subscriptions[0].max_rate_hz, 0.0);
  EXPECT_EQ(subscribe.subscriptions[1].max_rate_hz, 30.0);
  const auto set = std::get<protocol::SetParameters>(protocol::parse_client_text(
      R"({"op":"setParameters","parameters":[{"name":"/a","value":2},{"name":"/b","value":[1,2]}],"id":"q"})"));
  ASSERT_EQ(set.parameters.size(), 2u);
  EXPECT_EQ(std::get<double>(set.parameters[0].value), 2.0);
  EXPECT_EQ(std::get<std::vector<double>>(set.parameters[1].value).size(), 2u);
  EXPECT_EQ(set.id, "q");
  const auto fetch = std::get<protocol::FetchAsset>(protocol::parse_client_text(
      R"({"op":"fetchAsset","uri":"package://p/m.stl","requestId":7})"));
  EXPECT_EQ(fetch.request_id, 7u);
  EXPECT_TRUE(std::holds_alternative<protocol::GetParameters>(
      protocol::parse_client_text(R"({"op":"getParameters","parameterNames":[]})")));
  EXPECT_TRUE(std::holds_alternative<protocol::Unsupported>(
      protocol::parse_client_text(R"({"op":"subscribeConnectionGraph"})")));
}

// Each malformed message is refused with a line that says what is wrong.
TEST(BridgeProtocol, RefusesMalformedRequestsNamingTheProblem) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"{not json", "not JSON"},
      {"[1,2]", "'op'"},
      {R"({"op":"fly"})", "unknown op 'fly'"},
      {R"({"op":"subscribe"})", "'subscriptions'"},
      {R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})", "'id'"},
      {R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":1,"maxRateHz":-3}]})",
       "maxRateHz"},
      {R"({"op":"setParameters","parameters":[{"name":"/a"}]})", "no value"},
      {R"({"op":"setParameters","parameters":[{"name":"/a","value":{"x":1}}]})",
       "must be a number"},
      {R"({"op":"fetchAsset","uri":3,"requestId":1})", "'uri'"},
  };
  for (const auto& [text, expected] : cases) {
    try {
      protocol::parse_client_text(text);
      ADD_FAILURE() << text << " was accepted";
    } catch (const protocol::ProtocolError& error) {
      EXPECT_NE(std::string(error.what()).find(expected), std::string::npos)
          << text << " → " << error.what();
    }
  }
}

TEST(BridgeProtocol, ParsesBinaryClientFramesAndRefusesShortOnes) {
  const std::vector<std::uint8_t> data{0x01, 7, 0, 0, 0, 0xaa, 0xbb};
  const auto message = std::get<protocol::ClientMessageData>(protocol::parse_client_binary(data));
  EXPECT_EQ(message.channel_id, 7u);
  EXPECT_EQ(message.payload.size(), 2u);
  const std::vector<std::uint8_t> call{0x02, 3, 0, 0,   0,   9,   0,   0,   0,  4,
                                       0,    0, 0, 'j', 's', 'o', 'n', '{', '}'};
  const auto request = std::get<protocol::ServiceCallRequest>(protocol::parse_client_binary(call));
  EXPECT_EQ(request.service_id, 3u);
  EXPECT_EQ(request.call_id, 9u);
  EXPECT_EQ(request.encoding, "json");
  EXPECT_EQ(std::string(request.payload.begin(), request.payload.end()), "{}");
  for (const auto& bad :
       std::vector<std::vector<std::uint8_t>>{{},
                                              {0x01, 1, 0},
                                              {0x02, 1, 0, 0, 0, 1, 0, 0, 0, 200, 0, 0, 0, 'j'},
                                              {0x09, 0, 0, 0, 0}}) {
    EXPECT_THROW(protocol::parse_client_binary(bad), protocol::ProtocolError);
  }
}

TEST(BridgeProtocol, ServiceMessagesAreTheSpecs) {
  const std::string body = R"({"result":"ok"})";
  const auto response = protocol::service_call_response(
      2, 5, "json", std::span(reinterpret_cast<const std::uint8_t*>(body.data()), body.size()));
  EXPECT_EQ(response[0], 0x03);
  EXPECT_EQ(read_le(&response[1], 4), 2u);
  EXPECT_EQ(read_le(&response[5], 4), 5u);
  EXPECT_EQ(read_le(&response[9], 4), 4u);
  EXPECT_EQ(std::string(response.begin() + 13, response.end()), "json" + body);
  const protocol::Service service{4,   "/arm/controllers/list", "wbi.ListControllers", "json", "{}",
                                  "{}"};
  const auto advertised = json::parse(protocol::advertise_services(std::vector{service}));
  EXPECT_EQ(advertised["op"], "advertiseServices");
  EXPECT_EQ(advertised["services"][0]["id"], 4);
  EXPECT_EQ(advertised["services"][0]["request"]["encoding"], "json");
  const auto failure = json::parse(protocol::service_call_failure(4, 8, "refused"));
  EXPECT_EQ(failure["callId"], 8);
  const auto client_advertise = std::get<protocol::ClientAdvertise>(protocol::parse_client_text(
      R"({"op":"advertise","channels":[{"id":2,"topic":"wbi/arm/references/c/i","encoding":"json","schemaName":"x"}]})"));
  EXPECT_EQ(client_advertise.channels.at(0).topic, "wbi/arm/references/c/i");
}

OutgoingMessage data_message(std::uint32_t channel, std::size_t bytes) {
  return OutgoingMessage::data(channel, protocol::message_data_header(1, 0),
                               std::make_shared<const std::vector<std::uint8_t>>(bytes));
}

TEST(BridgeSendQueue, WakesTheWriterOnceUntilItDrains) {
  SendQueue queue(1u << 20);
  EXPECT_TRUE(queue.push(OutgoingMessage::json("a")));
  EXPECT_FALSE(queue.push(OutgoingMessage::json("b")));  // the writer is already awake
  EXPECT_EQ(*queue.take()->text, "a");
  EXPECT_EQ(*queue.take()->text, "b");
  EXPECT_FALSE(queue.take().has_value());  // now idle
  EXPECT_TRUE(queue.push(OutgoingMessage::json("c")));
}

TEST(BridgeSendQueue, DropsTheOldestDataNeverJsonAndCountsPerChannel) {
  SendQueue queue(10'000);
  queue.push(OutgoingMessage::json("advertise"));
  for (int i = 0; i < 100; ++i) {
    queue.push(data_message(i % 2 == 0 ? 1 : 2, 1000));
  }
  EXPECT_LE(queue.queued_bytes(), 10'000u);
  EXPECT_GT(queue.total_dropped(), 80u);
  const auto drops = queue.take_drops();
  EXPECT_EQ(drops.at(1) + drops.at(2), queue.total_dropped());
  EXPECT_TRUE(queue.take_drops().empty());  // reset once taken
  auto first = queue.take();
  ASSERT_TRUE(first && first->text);
  EXPECT_EQ(*first->text, "advertise");  // kept though it is the oldest
}

TEST(BridgeSendQueue, KeepsTheNewestSamples) {
  SendQueue queue(5 * (1000 + 64 + 13));
  for (std::uint32_t i = 0; i < 20; ++i) {
    queue.push(OutgoingMessage::data(7, protocol::message_data_header(i, 0),
                                     std::make_shared<const std::vector<std::uint8_t>>(1000)));
  }
  const auto oldest_kept = queue.take();
  ASSERT_TRUE(oldest_kept.has_value());
  EXPECT_EQ(read_le(&oldest_kept->header[1], 4), 15u);  // the last five of 20
}

class TemporaryFolder {
 public:
  TemporaryFolder()
      : path_(std::filesystem::temp_directory_path() /
              ("wbi_bridge_assets_" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_ / "served" / "pkg" / "meshes");
    std::ofstream(path_ / "served" / "pkg" / "meshes" / "link.stl") << "solid";
    std::ofstream(path_ / "secret.txt") << "no";
  }
  ~TemporaryFolder() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

TEST(BridgeAssets, ServesOnlyFilesInsideTheGivenFolders) {
  TemporaryFolder folder;
  AssetFolders assets;
  assets.add(folder.path() / "served");
  EXPECT_EQ(assets.read("package://pkg/meshes/link.stl").size(), 5u);
  EXPECT_EQ(assets.read("pkg/meshes/link.stl").size(), 5u);
  EXPECT_EQ(assets.read("file://" + (folder.path() / "served/pkg/meshes/link.stl").string()).size(),
            5u);
  for (const std::string& uri :
       {"file://" + (folder.path() / "secret.txt").string(),
        std::string("package://pkg/../../secret.txt"),
        std::string("package://pkg/meshes/missing.stl"), std::string("http://example.com/x.stl")}) {
    EXPECT_THROW(assets.read(uri), std::runtime_error) << uri;
  }
}

// The transforms put every link where the model's forward kinematics does.
TEST(BridgeFrameTransforms, ChainOfTheArmMatchesForwardKinematics) {
  const auto urdf = (wbi::test::source_dir() / "models" / "arm7.urdf").string();
  wbi::model::LoadOptions fixed;
  fixed.fixed_base = true;
  const auto model = wbi::model::load_urdf_file(urdf, fixed);
  std::vector<std::string> joints(model.joint_name.rbegin(),
                                  model.joint_name.rend());  // another order
  FrameTransforms transforms(urdf, false, joints);
  std::vector<double> q;
  for (std::size_t j = 0; j < joints.size(); ++j) {
    q.push_back(0.1 * static_cast<double>(j + 1));
  }
  const auto message =
      json::parse(transforms.message(1'500'000'000ull, q, Eigen::Isometry3d::Identity()));
  const auto& list = message["transforms"];
  // Compose the chain from the world to each link and compare with the model.
  std::map<std::string, Eigen::Isometry3d> world_T;
  world_T["world"] = Eigen::Isometry3d::Identity();
  for (const auto& t : list) {
    EXPECT_EQ(t["timestamp"]["sec"], 1);
    EXPECT_EQ(t["timestamp"]["nsec"], 500'000'000);
    const Eigen::Quaterniond r(t["rotation"]["w"], t["rotation"]["x"], t["rotation"]["y"],
                               t["rotation"]["z"]);
    EXPECT_NEAR(r.norm(), 1.0, 1e-12);
    Eigen::Isometry3d parent_T = Eigen::Isometry3d::Identity();
    parent_T.linear() = r.toRotationMatrix();
    parent_T.translation() << t["translation"]["x"], t["translation"]["y"], t["translation"]["z"];
    ASSERT_TRUE(world_T.count(t["parent_frame_id"]))
        << "parent before child: " << t["parent_frame_id"];
    world_T[t["child_frame_id"]] = world_T[t["parent_frame_id"]] * parent_T;
  }
  EXPECT_EQ(list.size(), transforms.link_count() - (model.frame_name[0] == "world" ? 1 : 0));
  wbi::model::Data data(model);
  Eigen::VectorXd qm(model.n_joints);
  for (std::size_t j = 0; j < joints.size(); ++j) {
    qm[model.joint_id(joints[j])] = q[j];
  }
  wbi::model::forward_kinematics(model, data, qm);
  for (int f = 0; f < model.n_frames(); ++f) {
    const auto& name = model.frame_name[f];
    if (name == "world") {
      continue;
    }
    EXPECT_TRUE(world_T[name].matrix().isApprox(wbi::model::frame_pose(model, data, f), 1e-12))
        << name;
  }
}

TEST(BridgeFrameTransforms, NamesAJointTheUrdfDoesNotHave) {
  const auto urdf = (wbi::test::source_dir() / "models" / "arm7.urdf").string();
  try {
    FrameTransforms transforms(urdf, false, {"joint_1", "elbow_of_another_robot"});
    ADD_FAILURE() << "accepted";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("elbow_of_another_robot"), std::string::npos)
        << error.what();
  }
}

}  // namespace
