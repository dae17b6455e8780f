// One owner per joint (issue 22 item 1): the claim rules on given inputs
// (JointClaims), then the robot's actuator side over real DDS participants: a
// claim is granted or refused naming the owner, a non-owner's commands never
// reach a claimed joint (counted per sender), a forced claim takes joints and
// the owners topic says so, a released or orphaned joint can be claimed again.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <wbi/dds/client.hpp>
#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "actuator_side.hpp"
#include "joint_claims.hpp"
#include "test_support.hpp"
#include "two_joint_toy.hpp"

namespace {

using wbi::robot::Claimant;
using wbi::robot::JointClaims;
using namespace std::chrono_literals;
using wbi::test::eventually;

constexpr std::int64_t kLapse = 100'000'000;  // 0.1 s, the default watchdog time

Claimant claimant(std::uint8_t participant, const char* name) {
  std::uint8_t guid[16] = {participant};
  return Claimant::of(guid, name);
}

const auto kNeverGone = [](const Claimant&) { return false; };

TEST(JointClaimRules, FirstClaimIsGrantedAndASecondIsRefusedNamingTheOwner) {
  JointClaims claims({"a", "b", "c"}, kLapse, false);
  const auto pd = claimant(1, "pd");
  const auto arms = claimant(2, "arms");
  const std::vector<int> ab{0, 1};
  EXPECT_TRUE(claims.claim(pd, ab, false, 0, kNeverGone).granted);
  EXPECT_EQ(claims.generation(), 1u);

  const std::vector<int> bc{1, 2};
  const auto refused = claims.claim(arms, bc, false, 1'000, kNeverGone);
  EXPECT_FALSE(refused.granted);
  ASSERT_EQ(refused.contested.size(), 1u);  // b only: c is free
  EXPECT_EQ(refused.contested[0].joint, 1);
  EXPECT_EQ(refused.contested[0].owner, pd);
  EXPECT_FALSE(claims.held(2)) << "a refused claim takes nothing, not even the free joints";

  EXPECT_TRUE(claims.claim(pd, ab, false, 2'000, kNeverGone).granted)
      << "a claim again: idempotent";
  EXPECT_EQ(claims.generation(), 1u);
}

TEST(JointClaimRules, OnlyTheOwnerCommandsAClaimedJointAndFreeJointsTakeAnyone) {
  JointClaims claims({"a", "b"}, kLapse, false);
  const auto pd = claimant(1, "pd");
  const std::vector<int> a{0};
  ASSERT_TRUE(claims.claim(pd, a, false, 0, kNeverGone).granted);
  const std::vector<std::uint16_t> both{0, 1};
  const std::vector<std::uint16_t> only_b{1};
  EXPECT_EQ(claims.first_refused(pd, std::span<const std::uint16_t>(both)), -1);
  EXPECT_EQ(claims.first_refused(claimant(2, "rogue"), std::span<const std::uint16_t>(both)), 0);
  EXPECT_EQ(claims.first_refused(claimant(2, "rogue"), std::span<const std::uint16_t>(only_b)), -1);
  const std::vector<std::uint16_t> out_of_range{41, 1};  // the joint controller names index 41
  EXPECT_EQ(
      claims.first_refused(claimant(2, "rogue"), std::span<const std::uint16_t>(out_of_range)), -1);
  // The name alone is not the owner: the same name from another participant is refused.
  EXPECT_EQ(claims.first_refused(claimant(2, "pd"), std::span<const std::uint16_t>(both)), 0);
  EXPECT_NE(claims.refusal(claimant(2, "pd"), 0).find("not by this sender's participant"),
            std::string::npos);

  JointClaims strict({"a", "b"}, kLapse, true);
  EXPECT_EQ(strict.first_refused(pd, std::span<const std::uint16_t>(only_b)), 0);
  EXPECT_NE(strict.refusal(pd, 1).find("require_claims"), std::string::npos);
}

TEST(JointClaimRules, AClaimEndsWhenItsOwnerIsSilentOrGoneAndCommandsRenewIt) {
  JointClaims claims({"a"}, kLapse, false);
  const auto pd = claimant(1, "pd");
  const auto arms = claimant(2, "arms");
  const std::vector<int> a{0};
  const std::vector<std::uint16_t> a16{0};
  ASSERT_TRUE(claims.claim(pd, a, false, 0, kNeverGone).granted);
  claims.commanded(pd, std::span<const std::uint16_t>(a16), 90'000'000);
  EXPECT_FALSE(claims.claim(arms, a, false, 150'000'000, kNeverGone).granted)
      << "commanded 60 ms ago: the claim stands";
  const auto after_silence = claims.claim(arms, a, false, 191'000'000, kNeverGone);
  ASSERT_TRUE(after_silence.granted) << "no command for 101 ms: the claim ended";
  ASSERT_EQ(after_silence.taken.size(), 1u);
  EXPECT_EQ(after_silence.taken[0].owner, pd);

  const auto gone =
      claims.claim(pd, a, false, 191'000'001, [&](const Claimant& owner) { return owner == arms; });
  EXPECT_TRUE(gone.granted) << "the owner's participant left: its claim ended at once";

  JointClaims no_watchdog({"a"}, 0, false);
  ASSERT_TRUE(no_watchdog.claim(pd, a, false, 0, kNeverGone).granted);
  EXPECT_FALSE(no_watchdog.claim(arms, a, false, 10'000'000'000, kNeverGone).granted)
      << "without a watchdog, silence never ends a claim";
}

TEST(JointClaimRules, ForceTakesAndReleaseFrees) {
  JointClaims claims({"a", "b"}, kLapse, false);
  const auto pd = claimant(1, "pd");
  const auto supervisor = claimant(3, "supervisor");
  const std::vector<int> ab{0, 1};
  const std::vector<int> b{1};
  ASSERT_TRUE(claims.claim(pd, ab, false, 0, kNeverGone).granted);
  const auto forced = claims.claim(supervisor, b, true, 1, kNeverGone);
  ASSERT_TRUE(forced.granted);
  ASSERT_EQ(forced.taken.size(), 1u);
  EXPECT_EQ(claims.owner(1), supervisor);
  EXPECT_EQ(claims.owner(0), pd);

  EXPECT_EQ(claims.release(pd, {}), std::vector<int>{0}) << "all of pd's joints: a";
  EXPECT_FALSE(claims.held(0));
  EXPECT_TRUE(claims.release(pd, b).empty()) << "b is not pd's to release";
  EXPECT_TRUE(claims.held(1));
  EXPECT_EQ(claims.generation(), 3u);
}

// ----- over DDS: the actuator side of robot "claimed" (joints a, b) -----

constexpr const char* kRobot = "claimed";

// A controller: its own participant, a claim client and a command publisher in it.
struct Controller {
  std::string name;
  wbi::dds::Participant participant;
  wbi::dds::Client<wbi::msg::JointClaimRequest, wbi::msg::JointClaimReply> client;
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands;

  explicit Controller(const std::string& controller)
      : name(controller),
        participant(controller),
        client(participant, wbi::dds::topics::claim_service(kRobot)),
        commands(participant, wbi::dds::topics::commands(kRobot), wbi::dds::qos::kCommand) {}

  wbi::msg::JointClaimReply request(wbi::msg::ClaimAction action, std::vector<std::string> joints,
                                    bool force = false) {
    wbi::msg::JointClaimRequest request;
    request.robot(kRobot);
    request.controller(name);
    request.action(action);
    request.force(force);
    for (const auto& joint : joints) {
      request.joints().push_back(joint);
    }
    wbi::msg::JointClaimReply reply;
    client.call(request, reply, 5s);
    return reply;
  }
  wbi::msg::JointClaimReply claim(std::vector<std::string> joints, bool force = false) {
    return request(wbi::msg::ClaimAction::CLAIM, std::move(joints), force);
  }
  void torque(std::vector<std::uint16_t> joints, std::vector<double> values) {
    wbi::msg::ActuatorCommand c;
    c.header().robot(kRobot);
    c.controller(name);
    c.joints(joints);
    c.modes(std::vector<wbi::msg::ControlMode>(joints.size(), wbi::msg::TORQUE));
    c.references(values);
    ASSERT_TRUE(commands.publish(c));
  }
};

struct Robot {
  wbi::dds::Participant participant{"robot"};
  wbi::runtime::StatusReport report;
  wbi::runtime::EventLog events;
  wbi::robot::ActuatorSide side{participant, kRobot, wbi::test::two_joint_description(kRobot),
                                {},          report, events};
  wbi::dds::Subscriber<wbi::msg::JointOwners> owners{
      participant, wbi::dds::topics::joint_owners(kRobot), wbi::dds::qos::kLatched};
  wbi::actuation::SensorReadings readings;
  wbi::actuation::JointCommands out;
  std::int64_t tick = 0;

  Robot() {
    readings.resize(wbi::test::two_joint_description(kRobot));
    readings.position.setZero();
    readings.velocity.setZero();
    out.resize(2);
    side.hold(readings, wbi::actuation::Time(0));
  }
  // One 1 ms tick; the commands it applies are those that arrived before it.
  void update() {
    const auto now = wbi::actuation::Time(++tick * 1'000'000);
    side.begin_tick(now);
    side.update(now, wbi::actuation::Duration(1'000'000), readings, out);
  }
  std::uint64_t counter(const char* name) { return report.counter(name).value(); }
  // The owners topic as the robot's own reader got it last.
  std::optional<wbi::msg::JointOwners> latest_owners() {
    auto latest = owners.latest();
    return latest ? std::optional(latest->sample) : std::nullopt;
  }
};

TEST(JointClaimsOverDds, ARogueNeverMovesAClaimedJointAndAForcedClaimTellsTheOwner) {
  Robot robot;
  Controller pd("pd");
  Controller rogue("rogue");

  const auto granted = pd.claim({"a", "b"});
  EXPECT_STREQ(granted.error().c_str(), "");
  ASSERT_TRUE(eventually([&] {
    const auto owners = robot.latest_owners();
    return owners && owners->generation() == 1;
  }));
  EXPECT_EQ(robot.latest_owners()->controllers()[1], "pd");
  EXPECT_EQ(robot.latest_owners()->participants()[1],
            std::string(pd.client.client_id()).substr(0, 24));

  const auto refused = rogue.claim({"b"});
  EXPECT_NE(std::string(refused.error().c_str()).find("b (held by 'pd')"), std::string::npos)
      << refused.error().c_str();
  ASSERT_EQ(refused.contested().size(), 1u);
  EXPECT_EQ(refused.contested()[0], "b");
  EXPECT_EQ(refused.owners()[0], "pd");
  EXPECT_EQ(robot.counter("claims_refused"), 1u);

  // The owner's command is applied; the rogue's (under its own name, then
  // under the owner's) is dropped whole and counted per sender.
  ASSERT_TRUE(pd.commands.wait_for_subscribers(1, 5s));
  ASSERT_TRUE(rogue.commands.wait_for_subscribers(1, 5s));
  pd.torque({0, 1}, {1.0, -1.0});
  ASSERT_TRUE(eventually([&] { return robot.counter("accepted_commands") == 1; }));
  rogue.torque({1}, {40.0});
  ASSERT_TRUE(eventually([&] { return robot.counter("rejected_commands") == 1; }));
  rogue.name = "pd";
  rogue.torque({1}, {40.0});
  ASSERT_TRUE(eventually([&] { return robot.counter("rejected_commands") == 2; }));
  robot.update();
  EXPECT_DOUBLE_EQ(robot.out.value[0], 1.0);
  EXPECT_DOUBLE_EQ(robot.out.value[1], -1.0) << "the rogue's 40 N·m never reached joint b";
  EXPECT_EQ(robot.counter("rejected_from/rogue"), 2u) << "its refused claim and its command";
  EXPECT_NE(robot.report.last_error().find("not by this sender's participant"), std::string::npos)
      << robot.report.last_error();
  rogue.name = "rogue";

  // A supervisor takes b by force: the owners topic says so, pd's next command is refused.
  Controller supervisor("supervisor");
  EXPECT_STREQ(supervisor.claim({"b"}, true).error().c_str(), "");
  ASSERT_TRUE(eventually([&] { return robot.latest_owners()->generation() == 2; }));
  EXPECT_EQ(robot.latest_owners()->controllers()[1], "supervisor");
  EXPECT_EQ(robot.latest_owners()->controllers()[0], "pd");
  pd.torque({0, 1}, {2.0, -2.0});
  ASSERT_TRUE(eventually([&] { return robot.counter("rejected_commands") == 3; }));
  EXPECT_NE(robot.report.last_error().find("joint 'b' is held by 'supervisor'"), std::string::npos)
      << robot.report.last_error();

  // pd releases what it holds (a); a is free again for anyone.
  EXPECT_STREQ(pd.request(wbi::msg::ClaimAction::RELEASE, {}).error().c_str(), "");
  ASSERT_TRUE(eventually([&] { return robot.latest_owners()->generation() == 3; }));
  EXPECT_EQ(robot.latest_owners()->controllers()[0], "");
  EXPECT_STREQ(rogue.claim({"a"}).error().c_str(), "");
  EXPECT_EQ(robot.counter("claims_granted"), 3u);
}

TEST(JointClaimsOverDds, AJointOfAParticipantThatLeftCanBeClaimedWithoutForce) {
  Robot robot;
  {
    Controller gone("gone");
    EXPECT_STREQ(gone.claim({"a"}).error().c_str(), "");
  }  // its participant leaves the domain (and says so)
  Controller next("next");
  std::string error = "not tried";
  // Discovery hears of the departure within the bound; until then the claim is refused.
  ASSERT_TRUE(eventually([&] {
    error = next.claim({"a"}).error().c_str();
    return error.empty();
  })) << error;
  EXPECT_EQ(robot.latest_owners() ? std::string(robot.latest_owners()->controllers()[0]) : "",
            "next");
}

TEST(JointClaimsOverDds, BadClaimsAreRefusedNamingWhatIsWrong) {
  Robot robot;
  Controller pd("pd");
  EXPECT_NE(std::string(pd.claim({"a", "elbow"}).error().c_str())
                .find("robot 'claimed' has no joint 'elbow'"),
            std::string::npos);
  EXPECT_NE(std::string(pd.claim({"a", "a"}).error().c_str()).find("joint 'a' appears twice"),
            std::string::npos);
  EXPECT_NE(std::string(pd.claim({}).error().c_str()).find("at least one joint"),
            std::string::npos);
  pd.name = "";
  EXPECT_NE(std::string(pd.claim({"a"}).error().c_str()).find("names its controller"),
            std::string::npos);
  EXPECT_FALSE(robot.latest_owners() && robot.latest_owners()->generation() > 0);
}

}  // namespace
