// wbi_test_event_injector: the faults of event_faults.sh that no wbi verb
// makes, each from a participant of its own (exit 0 when done, 1 otherwise):
//   bad-commands ROBOT N    N actuator commands from 'fuzzer' naming joint
//                           index 41 (out of range): each is rejected
//   force-claim ROBOT JOINT JOINT claimed with force as 'supervisor', taken from
//                           whoever holds it (the claim lapses when this exits)
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include <wbi/msg/claims.h>
#include <wbi/msg/commands.h>
#include <wbi/dds/client.hpp>
#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>

namespace {

using namespace std::chrono_literals;

int bad_commands(const std::string& robot, int count) {
  wbi::dds::Participant participant("event_injector");
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(
      participant, wbi::dds::topics::commands(robot), wbi::dds::qos::kCommand);
  if (!commands.wait_for_subscribers(1, 20s)) {
    std::fprintf(stderr, "no reader of %s within 20 s\n", commands.topic().c_str());
    return 1;
  }
  wbi::msg::ActuatorCommand command;
  command.header().robot(robot);
  command.controller("fuzzer");
  command.joints({41});
  command.modes({wbi::msg::POSITION});
  command.references({0.0});
  for (int k = 0; k < count; ++k) {
    command.header().seq(static_cast<std::uint64_t>(k));
    if (!commands.publish(command)) {
      std::fprintf(stderr, "command %d not sent\n", k);
      return 1;
    }
  }
  return commands.wait_acknowledged(10s) ? 0 : 1;
}

int force_claim(const std::string& robot, const std::string& joint) {
  wbi::dds::Participant participant("event_injector");
  wbi::dds::Client<wbi::msg::JointClaimRequest, wbi::msg::JointClaimReply> claims(
      participant, wbi::dds::topics::claim_service(robot));
  wbi::msg::JointClaimRequest request;
  request.robot(robot);
  request.controller("supervisor");
  request.action(wbi::msg::ClaimAction::CLAIM);
  request.force(true);
  request.joints().push_back(joint);
  wbi::msg::JointClaimReply reply;
  claims.call(request, reply, 20s);
  if (reply.error().size() > 0) {
    std::fprintf(stderr, "claim refused: %s\n", reply.error().c_str());
    return 1;
  }
  std::printf("supervisor holds %s\n", joint.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string action = argc == 4 ? argv[1] : "";
  try {
    if (action == "bad-commands") {
      return bad_commands(argv[2], std::stoi(argv[3]));
    }
    if (action == "force-claim") {
      return force_claim(argv[2], argv[3]);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wbi_test_event_injector %s: %s\n", action.c_str(), e.what());
    return 1;
  }
  std::fprintf(stderr,
               "usage: wbi_test_event_injector bad-commands ROBOT N | force-claim ROBOT JOINT\n");
  return 1;
}
