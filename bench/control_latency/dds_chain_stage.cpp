// wbi_bench_dds_chain_stage --role ROLE [--robot NAME]
//
// One stage of the raw five-hop chain (bench_control_latency.cpp, part (c)):
// the demo's DDS traffic with nothing between the hops. Each stage is its own
// process and participant, reads and writes the demo's message types on the
// demo's topics and QoS profiles, and relays in the reader's callback:
//
//   robot          writes a SensorSample (7 encoders) every 1 ms; reads the commands
//   estimator      sensors  -> StateEstimate (q, dq, ddq), header copied
//   controller     state    -> ModelRequest (gravity forces at q)
//                  reply    -> ActuatorCommand (7 torques), tick and source stamp
//                              of the sensor sample, as the proxy writes them
//   model_service  request  -> ModelReply (one 13 x 1 result)
//
// So robot -> estimator -> controller -> model service -> controller -> robot
// are the demo's five hops, without the estimate, the control cycle, the
// model's computation, the runtime's threads or the proxy. Runs until SIGTERM
// or SIGINT.
#include <pthread.h>

#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <wbi/msg/commands.h>
#include <wbi/msg/model.h>
#include <wbi/msg/sensors.h>
#include <wbi/msg/state.h>
#include <wbi/dds/participant.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/rpc.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

namespace {

namespace dds = wbi::dds;
namespace msg = wbi::msg;

constexpr std::size_t kJoints = 7;  // the demo's arm
constexpr std::size_t kNv = kJoints + 6;

// A stage: its readers relay from their callbacks, from construction to destruction.
class Stage {
 public:
  virtual ~Stage() = default;
};

class RobotStage : public Stage {
 public:
  RobotStage(dds::Participant& participant, const std::string& robot)
      : sensors_(participant, dds::topics::sensors(robot), dds::qos::kStream),
        commands_(participant, dds::topics::commands(robot), dds::qos::kCommand,
                  [](const msg::ActuatorCommand&, const dds::detail::SampleInfo&) {}) {
    sample_.header().robot(robot);
    sample_.encoder_position().assign(kJoints, 0.1);
    ticker_ = std::thread([this] { tick(); });
  }
  ~RobotStage() override {
    stop_ = true;
    ticker_.join();
  }

 private:
  // 1 kHz on the steady clock, as the simulated robot in real time.
  void tick() {
    auto next = std::chrono::steady_clock::now();
    for (std::uint64_t seq = 0; !stop_; ++seq) {
      next += std::chrono::milliseconds(1);
      std::this_thread::sleep_until(next);  // the robot's period
      sample_.header().seq(seq);
      sample_.header().stamp_ns(static_cast<std::int64_t>(seq + 1) * 1'000'000);
      sensors_.publish(sample_);
    }
  }

  dds::Publisher<msg::SensorSample> sensors_;
  dds::Subscriber<msg::ActuatorCommand> commands_;
  msg::SensorSample sample_;
  std::atomic<bool> stop_{false};
  std::thread ticker_;
};

class EstimatorStage : public Stage {
 public:
  EstimatorStage(dds::Participant& participant, const std::string& robot)
      : state_(participant, dds::topics::state(robot), dds::qos::kStream),
        sensors_(participant, dds::topics::sensors(robot), dds::qos::kStream,
                 [this](const msg::SensorSample& sample, const dds::detail::SampleInfo&) {
                   relay(sample);
                 }) {}

 private:
  void relay(const msg::SensorSample& sample) {
    estimate_.header() = sample.header();
    estimate_.q() = sample.encoder_position();
    estimate_.dq().assign(kJoints, 0.0);
    estimate_.ddq().assign(kJoints, 0.0);
    state_.publish(estimate_);
  }

  dds::Publisher<msg::StateEstimate> state_;
  msg::StateEstimate estimate_;  // the readers' callbacks run on one DDS thread
  dds::Subscriber<msg::SensorSample> sensors_;
};

class ControllerStage : public Stage {
 public:
  ControllerStage(dds::Participant& participant, const std::string& robot)
      : requests_(participant, dds::topics::service_request(dds::topics::model_service(robot)),
                  dds::qos::kRequestReply),
        commands_(participant, dds::topics::commands(robot), dds::qos::kCommand),
        replies_(participant, dds::topics::service_reply(dds::topics::model_service(robot)),
                 dds::qos::kRequestReply,
                 [this](const msg::ModelReply& reply, const dds::detail::SampleInfo&) {
                   on_reply(reply);
                 }),
        states_(participant, dds::topics::state(robot), dds::qos::kStream,
                [this](const msg::StateEstimate& state, const dds::detail::SampleInfo&) {
                  on_state(state);
                }) {
    request_.client_id("chain");
    request_.robot(robot);
    request_.operations().resize(1);
    request_.operations()[0].operation(msg::GRAVITY_FORCES);
    request_.state().dq().assign(kJoints, 0.0);
    request_.state().gravity().z(-9.81);
    command_.header().robot(robot);
    command_.controller("pd_gravity");
    for (std::uint16_t j = 0; j < kJoints; ++j) {
      command_.joints().push_back(j);
    }
    command_.modes().assign(kJoints, msg::TORQUE);
    command_.references().assign(kJoints, 0.0);
  }

 private:
  // The request's seq is the sensor sample's; its stamp waits here for the reply.
  void on_state(const msg::StateEstimate& state) {
    std::lock_guard lock(mutex_);
    stamps_[state.header().seq() % stamps_.size()] = state.header().stamp_ns();
    request_.seq(state.header().seq());
    request_.state().q() = state.q();
    requests_.publish(request_);
  }

  void on_reply(const msg::ModelReply& reply) {
    if (reply.results().empty() || reply.results()[0].data().size() < kNv) {
      return;
    }
    std::lock_guard lock(mutex_);
    const auto& gravity = reply.results()[0].data();
    for (std::size_t j = 0; j < kJoints; ++j) {
      command_.references()[j] = gravity[6 + j];
    }
    command_.tick(reply.seq());
    command_.source_stamp_ns(stamps_[reply.seq() % stamps_.size()]);
    command_.header().seq(command_.header().seq() + 1);
    command_.header().stamp_ns(command_.source_stamp_ns());
    commands_.publish(command_);
  }

  dds::Publisher<msg::ModelRequest> requests_;
  dds::Publisher<msg::ActuatorCommand> commands_;
  std::mutex mutex_;  // the two readers may call back on two threads
  std::array<std::int64_t, 64> stamps_{};
  msg::ModelRequest request_;
  msg::ActuatorCommand command_;
  dds::Subscriber<msg::ModelReply> replies_;
  dds::Subscriber<msg::StateEstimate> states_;
};

class ModelServiceStage : public Stage {
 public:
  ModelServiceStage(dds::Participant& participant, const std::string& robot)
      : replies_(participant, dds::topics::service_reply(dds::topics::model_service(robot)),
                 dds::qos::kRequestReply),
        requests_(participant, dds::topics::service_request(dds::topics::model_service(robot)),
                  dds::qos::kRequestReply,
                  [this](const msg::ModelRequest& request, const dds::detail::SampleInfo&) {
                    on_request(request);
                  }) {
    reply_.results().resize(1);
    reply_.results()[0].operation(msg::GRAVITY_FORCES);
    reply_.results()[0].rows(kNv);
    reply_.results()[0].cols(1);
    reply_.results()[0].data().assign(kNv, 1.0);
  }

 private:
  void on_request(const msg::ModelRequest& request) {
    reply_.client_id(request.client_id());
    reply_.seq(request.seq());
    replies_.publish(reply_);
  }

  dds::Publisher<msg::ModelReply> replies_;
  msg::ModelReply reply_;
  dds::Subscriber<msg::ModelRequest> requests_;
};

std::unique_ptr<Stage> make_stage(const std::string& role, dds::Participant& participant,
                                  const std::string& robot) {
  if (role == "robot") return std::make_unique<RobotStage>(participant, robot);
  if (role == "estimator") return std::make_unique<EstimatorStage>(participant, robot);
  if (role == "controller") return std::make_unique<ControllerStage>(participant, robot);
  if (role == "model_service") return std::make_unique<ModelServiceStage>(participant, robot);
  throw std::invalid_argument(
      "--role: must be robot, estimator, controller or model_service, got '" + role + "'");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string role, robot = "chain";
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if ((arg == "--role" || arg == "--robot") && i + 1 < argc) {
        (arg == "--role" ? role : robot) = argv[++i];
      } else if (arg == "--help" || arg == "-h") {
        std::cout << "usage: wbi_bench_dds_chain_stage --role robot|estimator|controller|"
                     "model_service [--robot NAME (chain)]\n";
        return 0;
      } else {
        throw std::invalid_argument("unknown option or missing value: " + arg + " (see --help)");
      }
    }
    if (role.empty()) {
      throw std::invalid_argument("--role is required (see --help)");
    }
    // SIGTERM and SIGINT are taken by sigwait below, on every thread.
    sigset_t stop_signals;
    sigemptyset(&stop_signals);
    sigaddset(&stop_signals, SIGTERM);
    sigaddset(&stop_signals, SIGINT);
    pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

    dds::Participant participant("chain_" + role);  // joins as the demo's processes do (WBI_*)
    const auto stage = make_stage(role, participant, robot);
    int signal = 0;
    sigwait(&stop_signals, &signal);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "wbi_bench_dds_chain_stage: " << e.what() << "\n";
    return 1;
  }
}
