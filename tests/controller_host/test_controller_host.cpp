// The controller host on the project's arm, simulated in lockstep in this
// process, over real DDS: a switch at a tick boundary with a small torque
// step, refused switches and parameters that change nothing, a live gain
// change that changes the motion, and the fallback to hold when a controller
// throws.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <future>
#include <optional>

#include <wbi/controllers/controller_host.hpp>
#include <wbi/controllers/pd_gravity_controller.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/sim_rig/in_process_robot.hpp>

#include "allocation_counter.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::controllers::Controller;
using wbi::controllers::ControllerHost;
using wbi::controllers::ParameterSpec;
using wbi::controllers::ParameterTable;

const std::vector<std::string> kArm{"joint_1", "joint_2", "joint_3", "joint_4",
                                    "joint_5", "joint_6", "joint_7"};
const std::vector<double> kTarget{0.3, 0.6, -0.2, 1.2, 0.1, 0.9, 0.0};
constexpr double kPeriod = 0.001;

// Sends zero torque, and throws at its `throw_at`-th update: a controller with a bug.
class ThrowingController final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override {
    return {{.name = "throw_at", .default_value = {5.0}, .min = 1.0}};
  }
  void configure(wbi::WholeBodyInterface& robot, const ParameterTable& parameters) override {
    throw_at_ = static_cast<int>(parameters.value(0));
    tau_.setZero(robot.dofs());
  }
  void activate(const wbi::RobotState&) override { updates_ = 0; }
  bool update(double, double) override {
    if (++updates_ >= throw_at_) {
      throw std::runtime_error("index 9 out of range");
    }
    return true;
  }
  const Eigen::VectorXd& command() const override { return tau_; }

 private:
  int throw_at_ = 5, updates_ = 0;
  Eigen::VectorXd tau_;
};

// The simulated arm, its estimator, and a host with pd (active), hold and a
// thrower, on robot `robot` (or the controllers `hosting` adds). Each tick()
// waits for the next estimate, as the host's component does with wait_for_state.
class HostedArm {
 public:
  using Hosting = std::function<void(ControllerHost&)>;
  explicit HostedArm(const std::string& robot, double gain_scale = 1.0, Hosting hosting = {})
      : rig_("controller_host",
             "robot: " + robot + "\nconfig: " + config() +
                 "\nlockstep: true\nlockstep_controllers: [host]\n",
             "robot: " + robot + "\nmethod: backward-difference\ncutoff: 100\n") {
    wbi::DdsInterfaceOptions options;
    options.robot = robot;
    options.controller = "host";
    options.urdf = wbi::test::project_model("arm7.urdf").string();
    options.max_age_s = 5.0;  // lockstep: time is the simulation's
    arm_ = wbi::make_dds_interface(options);
    arm_->add_joints(kArm);
    rig_.start_simulation();
    arm_->init(20s);
    q_.setZero(arm_->dofs());
    state_ = wbi::RobotState(arm_->dofs());
    host_.emplace(*arm_, report_, events_, ControllerHost::Options{});
    if (hosting) {
      hosting(*host_);
      return;
    }
    ParameterTable& pd =
        host_->add("pd", "pd_gravity", std::make_unique<wbi::controllers::PdGravityController>());
    pd.set(pd.index("target"), kTarget);
    pd.set(pd.index("gain_scale"), std::vector<double>{gain_scale});
    host_->configure("pd");
    host_->add("hold", "hold", wbi::controllers::make_hold_controller());
    host_->configure("hold");
    host_->add("thrower", "thrower", std::make_unique<ThrowingController>());
    host_->configure("thrower");
    host_->set_initial("pd");
  }
  ~HostedArm() {
    rig_.sim().shutdown();
    rig_.estimator().shutdown();
  }

  static std::string config() {
    return (wbi::test::source_dir() / "deploy" / "robots" / "arm.yaml").string();
  }

  void tick() {
    // The first tick answers the estimate init() read; each later one the next.
    arm_->state().read_robot_state(
        state_, time_s_ == 0.0 ? wbi::ReadMode::latest : wbi::ReadMode::blocking);
    q_ = state_.q;
    host_->tick(time_s_, kPeriod);
    time_s_ += kPeriod;
  }
  // The allocations of the host's ticks (on this thread; the test's blocking
  // wait is not counted) less those of as many bare command writes. Fast DDS
  // 2.9 allocates inside every reliable write (wbi_proxy/README.md,
  // "Allocations per tick"), so the host is compared with the write it makes:
  // the difference is the host's own. The bare write resends the command the
  // tick sent (same values, same tick): the run does not change.
  double host_allocations_per_tick(int ticks) {
    long host = 0, writes = 0;
    for (int k = 0; k < ticks; ++k) {
      arm_->state().read_robot_state(state_, wbi::ReadMode::blocking);
      const long before = wbi::test::thread_allocation_count();
      host_->tick(time_s_, kPeriod);
      const long after_tick = wbi::test::thread_allocation_count();
      arm_->set_control_reference(host_->last_command());
      writes += wbi::test::thread_allocation_count() - after_tick;
      host += after_tick - before;
      time_s_ += kPeriod;
    }
    return static_cast<double>(host - writes) / ticks;
  }
  void run(int ticks) {
    for (int k = 0; k < ticks; ++k) {
      tick();
    }
  }
  // Ticks until `request` returns (it waits for the loop to apply it).
  template <class Result>
  Result tick_until(std::future<Result>& request) {
    for (int k = 0; k < 5000 && request.wait_for(0s) != std::future_status::ready; ++k) {
      tick();
    }
    return request.get();
  }
  double error_to_target() const {
    double error = 0.0;
    for (int i = 0; i < q_.size(); ++i) {
      error = std::max(error, std::abs(q_[i] - kTarget[static_cast<std::size_t>(i)]));
    }
    return error;
  }
  std::uint64_t counter(const std::string& name) const {
    for (std::size_t i = 0; i < report_.counter_count(); ++i) {
      if (report_.counter_name(i) == name) {
        return report_.counter_value(i);
      }
    }
    return 0;
  }

  ControllerHost& host() { return *host_; }
  wbi::runtime::StatusReport& report() { return report_; }
  // The events emitted since the last call, in order.
  std::vector<wbi::runtime::EventRecord> take_events() {
    std::vector<wbi::runtime::EventRecord> taken;
    wbi::runtime::EventRecord event;
    while (events_.pop(event)) {
      taken.push_back(event);
    }
    return taken;
  }

 private:
  wbi::sim_rig::InProcessRobot rig_;
  std::unique_ptr<wbi::WholeBodyInterface> arm_;
  wbi::runtime::StatusReport report_;
  wbi::runtime::EventLog events_;
  std::optional<ControllerHost> host_;
  wbi::RobotState state_;
  Eigen::VectorXd q_;
  double time_s_ = 0.0;
};

TEST(ControllerHost, SwitchesAtATickBoundaryWithoutATorqueJump) {
  HostedArm arm("host_switch");
  arm.run(1500);
  EXPECT_EQ(arm.host().active(), "pd");
  EXPECT_LT(arm.error_to_target(), 0.02) << "pd reached the target";
  auto request =
      std::async(std::launch::async, [&] { return arm.host().request_switch({"hold"}, {"pd"}); });
  const auto result = arm.tick_until(request);
  ASSERT_TRUE(result.done) << result.text;
  std::printf("%s\n", result.text.c_str());
  EXPECT_EQ(arm.host().active(), "hold");
  // hold's first command continues pd's last (its blend): no step at the switch.
  EXPECT_LT(result.torque_step, 0.05) << result.text;
  EXPECT_EQ(arm.counter("switches"), 1u);
  const auto events = arm.take_events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, wbi::EventKind::controller_switched);
  EXPECT_EQ(std::string(events[0].text.data()).find("pd → hold at t = "), 0u)
      << events[0].text.data();
  arm.run(500);
  EXPECT_LT(arm.error_to_target(), 0.03) << "hold keeps the posture it took over";
}

// A real-time loop: after start-up, a tick (parameters staged and applied,
// the controller's update, the command sent) allocates nothing of the host's.
TEST(ControllerHost, ATickAllocatesNothingOfItsOwn) {
  HostedArm arm("host_allocations");
  arm.run(20);
  arm.host().set_parameter("pd", "gain_scale", {0.8});
  EXPECT_EQ(arm.host_allocations_per_tick(200), 0.0);
  EXPECT_EQ(arm.counter("parameter_changes"), 1u);
  const auto events = arm.take_events();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].kind, wbi::EventKind::parameter_changed);
  EXPECT_STREQ(events[0].text.data(), "pd.gain_scale = 0.8 (from the next tick)");
}

TEST(ControllerHost, ARefusedSwitchChangesNothing) {
  HostedArm arm("host_refuse");
  arm.run(10);
  const auto unknown = arm.host().request_switch({"balance"}, {"pd"});
  EXPECT_FALSE(unknown.done);
  EXPECT_NE(unknown.text.find("unknown controller 'balance'"), std::string::npos) << unknown.text;
  const auto not_active = arm.host().request_switch({"thrower"}, {"hold"});
  EXPECT_FALSE(not_active.done);
  EXPECT_NE(not_active.text.find("'hold' is not active"), std::string::npos) << not_active.text;
  const auto both = arm.host().request_switch({"hold"}, {});
  EXPECT_FALSE(both.done);
  EXPECT_NE(both.text.find("--deactivate pd"), std::string::npos) << both.text;
  arm.run(10);
  EXPECT_EQ(arm.host().active(), "pd");
  EXPECT_EQ(arm.counter("refused_switches"), 3u);
  EXPECT_EQ(arm.counter("switches"), 0u);
}

TEST(ControllerHost, ARefusedParameterChangesNothing) {
  HostedArm arm("host_param_refused");
  arm.run(10);
  try {
    arm.host().set_parameter("pd", "gain_scale", {20.0});
    FAIL() << "20 is out of range";
  } catch (const wbi::Error& e) {
    EXPECT_STREQ(e.what(), "pd: gain_scale = 20 is outside [0, 10]");
  }
  EXPECT_THROW(arm.host().set_parameter("pd", "bandwidth_hz", {10.0}), wbi::Error)
      << "not live while pd is active";
  EXPECT_NO_THROW(arm.host().set_parameter("hold", "bandwidth_hz", {1.0})) << "hold is inactive";
  arm.run(10);
  const auto& pd = arm.host().parameters("pd");
  EXPECT_EQ(pd.snapshot(pd.index("gain_scale"))[0], 1.0);
  EXPECT_EQ(pd.snapshot(pd.index("bandwidth_hz"))[0], 5.0);
}

// A waiter on a staged change sleeps until the tick that applies it wakes it
// (the host's service answers `wbi param set` so), active or inactive
// controller alike; without a tick it gives up at its timeout.
TEST(ControllerHost, AParameterWaiterWakesAtTheTickThatAppliesTheChange) {
  HostedArm arm("host_param_wait");
  arm.run(10);
  for (const char* name : {"pd", "hold"}) {
    const std::uint64_t before = arm.host().parameters(name).generation();
    arm.host().set_parameter(name, "gain_scale", {0.9});
    EXPECT_FALSE(arm.host().wait_for_parameters(name, before, 20ms)) << name << ": no tick yet";
    auto waiter = std::async(std::launch::async,
                             [&] { return arm.host().wait_for_parameters(name, before, 10s); });
    EXPECT_EQ(waiter.wait_for(20ms), std::future_status::timeout) << name;
    arm.run(1);
    // One tick applies it; a waiter caught between its check and its wait is
    // woken at the next one.
    if (waiter.wait_for(100ms) != std::future_status::ready) {
      arm.run(1);
    }
    ASSERT_EQ(waiter.wait_for(1s), std::future_status::ready) << name;
    EXPECT_TRUE(waiter.get()) << name;
    EXPECT_NE(arm.host().parameters(name).generation(), before) << name;
  }
}

// Half the gains from the first tick, in one run, and halved live at the same
// tick in another: the same motion, and slower than with the full gains.
TEST(ControllerHost, ALiveGainChangeChangesTheMotion) {
  double full = 0.0, halved_live = 0.0;
  {
    HostedArm arm("host_gain_full");
    arm.run(300);
    full = arm.error_to_target();
  }
  {
    HostedArm arm("host_gain_live");
    arm.run(1);
    arm.host().set_parameter("pd", "gain_scale", {0.5});
    arm.run(299);
    halved_live = arm.error_to_target();
    EXPECT_EQ(arm.counter("parameter_changes"), 1u);
  }
  EXPECT_GT(halved_live, 1.5 * full) << "full gains: " << full << " rad, halved: " << halved_live;
}

TEST(ControllerHost, AControllerThatThrowsFallsBackToHold) {
  HostedArm arm("host_fallback");
  arm.run(500);
  auto request = std::async(std::launch::async,
                            [&] { return arm.host().request_switch({"thrower"}, {"pd"}); });
  ASSERT_TRUE(arm.tick_until(request).done);
  arm.run(20);  // throws at its 5th update
  EXPECT_EQ(arm.host().active(), "hold");
  EXPECT_EQ(arm.counter("fallbacks"), 1u);
  const std::string error = arm.report().last_error();
  EXPECT_NE(error.find("controller 'thrower' threw in update (index 9 out of range)"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("fell back to 'hold'"), std::string::npos) << error;
  const auto events = arm.take_events();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].kind, wbi::EventKind::controller_switched);
  EXPECT_EQ(events[1].kind, wbi::EventKind::controller_fallback);
  EXPECT_EQ(events[1].severity, wbi::EventSeverity::warning);
  EXPECT_STREQ(events[1].text.data(), error.c_str());
}

// Several controllers on one host: pd on the shoulder and elbow (joints 1-4),
// a second pd on the wrist (5-7), hold on nothing; and a thrower that may
// take the wrist.
const std::vector<std::string> kShoulder{"joint_1", "joint_2", "joint_3", "joint_4"};
const std::vector<std::string> kWrist{"joint_5", "joint_6", "joint_7"};

void host_two_sets(ControllerHost& host) {
  for (const auto& [name, joints] :
       {std::pair{"shoulder", kShoulder}, std::pair{"wrist", kWrist}}) {
    ParameterTable& pd =
        host.add(name, "pd_gravity", std::make_unique<wbi::controllers::PdGravityController>());
    pd.set(pd.index("target"), kTarget);
    host.set_joints(name, joints);
    host.configure(name);
  }
  host.add("thrower", "thrower", std::make_unique<ThrowingController>());
  host.set_joints("thrower", kWrist);
  host.configure("thrower");
  host.add("hold", "hold", wbi::controllers::make_hold_controller());
  host.configure("hold");
  host.set_initial(std::vector<std::string>{"shoulder", "wrist"});
}

// The shoulder's commands of a run without the switch, tick by tick from 1.5 s.
std::vector<Eigen::VectorXd> commands_without_a_switch(int ticks) {
  HostedArm arm("host_two_sets_plain", 1.0, host_two_sets);
  arm.run(1500);
  std::vector<Eigen::VectorXd> commands;
  for (int k = 0; k < ticks; ++k) {
    arm.run(1);
    commands.push_back(arm.host().last_command());
  }
  return commands;
}

TEST(ControllerHostJointSets, TwoControllersActiveOnDisjointJoints) {
  const auto plain = commands_without_a_switch(1000);
  HostedArm arm("host_two_sets", 1.0, host_two_sets);
  arm.run(1500);
  EXPECT_EQ(arm.host().active(), "shoulder, wrist");
  EXPECT_LT(arm.error_to_target(), 0.02) << "each set reached its target";
  // The wrist to hold and back, staged on the loop's thread (as a schedule
  // does) so that the switch is this tick's: the shoulder's command then is
  // the one of the run without a switch, to the bit (lockstep: the same state).
  const auto tick_of = [](double time_s) {
    return static_cast<std::size_t>(std::lround((time_s - 1.5) / kPeriod));
  };
  ASSERT_EQ(arm.host().schedule_switch("hold", "wrist"), "");
  arm.run(1);
  const auto held = arm.host().last_switch();
  ASSERT_TRUE(held.done) << held.text;
  std::printf("%s\n", held.text.c_str());
  EXPECT_EQ(held.from, "wrist");
  EXPECT_EQ(held.to, "hold");
  EXPECT_EQ(arm.host().active(), "shoulder, hold");
  EXPECT_LT(held.torque_step_switched, 0.05) << held.text;
  ASSERT_LT(tick_of(held.time_s), plain.size());

  EXPECT_EQ(arm.host().last_command().head(4), plain[tick_of(held.time_s)].head(4))
      << "the switch changed the shoulder's command";
  arm.run(300);
  auto back =
      std::async(std::launch::async, [&] { return arm.host().request_switch({"wrist"}, {}); });
  const auto resumed = arm.tick_until(back);
  ASSERT_TRUE(resumed.done) << resumed.text;
  std::printf("%s\n", resumed.text.c_str());
  EXPECT_EQ(resumed.from, "hold");
  EXPECT_EQ(arm.host().active(), "shoulder, wrist");
  EXPECT_LT(resumed.torque_step_switched, 0.05) << resumed.text;
  arm.run(500);
  EXPECT_LT(arm.error_to_target(), 0.03);
}

TEST(ControllerHostJointSets, OverlappingSetsAreRefusedWhole) {
  HostedArm arm("host_overlap", 1.0, host_two_sets);
  arm.run(10);
  const auto overlap = arm.host().request_switch({"thrower"}, {});
  EXPECT_FALSE(overlap.done);
  EXPECT_NE(overlap.text.find("'wrist' is active on the same joints as 'thrower' (joint_5, "
                              "joint_6, joint_7): deactivate it in the same switch"),
            std::string::npos)
      << overlap.text;
  const auto nothing = arm.host().request_switch({"hold"}, {});
  EXPECT_FALSE(nothing.done);
  EXPECT_NE(nothing.text.find("nothing to hold"), std::string::npos) << nothing.text;
  arm.run(10);
  EXPECT_EQ(arm.host().active(), "shoulder, wrist");
  EXPECT_EQ(arm.counter("switches"), 0u);
  EXPECT_EQ(arm.counter("refused_switches"), 2u);
}

// One of two active controllers throws: hold takes its joints, and only those.
TEST(ControllerHostJointSets, AFallbackMovesOnlyThatControllersJointsToHold) {
  HostedArm arm("host_set_fallback", 1.0, host_two_sets);
  arm.run(500);
  auto request = std::async(std::launch::async,
                            [&] { return arm.host().request_switch({"thrower"}, {"wrist"}); });
  ASSERT_TRUE(arm.tick_until(request).done);
  const Eigen::VectorXd before = arm.host().last_command();
  arm.run(20);  // throws at its 5th update
  EXPECT_EQ(arm.host().active(), "shoulder, hold");
  EXPECT_EQ(arm.counter("fallbacks"), 1u);
  EXPECT_NE(arm.report().last_error().find("controller 'thrower' threw in update"),
            std::string::npos);
  arm.run(500);
  EXPECT_LT(arm.error_to_target(), 0.05) << "the shoulder kept its target, hold the wrist";
  EXPECT_TRUE(arm.host().last_command().head(4) != before.head(4)) << "the shoulder still commands";
}

// A planner chained to a controller of the same host: its point for this
// tick's state reaches the controller in the same tick, without DDS.
class TargetPlanner final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override { return {}; }
  std::vector<wbi::controllers::ReferenceSpec> outputs() const override {
    return {{.name = "target", .unit = "rad", .size = 7}};
  }
  void bind_outputs(std::span<wbi::controllers::ReferenceOutput* const> outputs) override {
    output_ = outputs[0];
  }
  bool commands_joints() const override { return false; }
  void configure(wbi::WholeBodyInterface& robot, const ParameterTable&) override {
    robot_ = &robot;
    state_ = wbi::RobotState(robot.dofs());
  }
  void activate(const wbi::RobotState&) override {}
  bool update(double, double) override {
    robot_->state().read_robot_state(state_, wbi::ReadMode::latest);
    output_->write(state_.stamp.source_ns, kTarget);
    return true;
  }
  const Eigen::VectorXd& command() const override { return none_; }

 private:
  wbi::WholeBodyInterface* robot_ = nullptr;
  wbi::controllers::ReferenceOutput* output_ = nullptr;
  wbi::RobotState state_;
  Eigen::VectorXd none_;
};

// PD + gravity towards its reference input `target` (zero torque until one came).
class FollowerPd final : public Controller {
 public:
  std::vector<ParameterSpec> parameters() const override { return {}; }
  std::vector<wbi::controllers::ReferenceSpec> references() const override {
    return {{.name = "target", .unit = "rad", .size = 7, .max_age_s = 0.0005}};
  }
  void bind_references(std::span<wbi::controllers::ReferenceInput* const> inputs) override {
    input_ = inputs[0];
  }
  void configure(wbi::WholeBodyInterface& robot, const ParameterTable&) override {
    robot_ = &robot;
    state_ = wbi::RobotState(robot.dofs());
    g_.setZero(robot.dofs() + 6);
    tau_.setZero(robot.dofs());
  }
  void activate(const wbi::RobotState&) override {
    robot_->set_control_mode(wbi::ControlMode::torque);
  }
  bool update(double, double) override {
    robot_->state().read_robot_state(state_, wbi::ReadMode::latest);
    const auto status = input_->at(state_.stamp.source_ns, [&] { return state_.q; });
    fresh_ += status == wbi::controllers::ReferenceStatus::fresh;
    robot_->model().gravity_forces(state_.q, state_.world_H_base, {0, 0, -9.81}, g_);
    tau_ = g_.tail(robot_->dofs()) - 100.0 * (state_.q - input_->position()) - 10.0 * state_.dq;
    return true;
  }
  const Eigen::VectorXd& command() const override { return tau_; }
  int fresh() const { return fresh_; }

 private:
  wbi::WholeBodyInterface* robot_ = nullptr;
  wbi::controllers::ReferenceInput* input_ = nullptr;
  wbi::RobotState state_;
  Eigen::VectorXd g_, tau_;
  int fresh_ = 0;
};

TEST(ControllerHostChaining, APlannersPointReachesItsControllerInTheSameTick) {
  FollowerPd* follower = nullptr;
  HostedArm arm("host_chain", 1.0, [&](ControllerHost& host) {
    auto owned = std::make_unique<FollowerPd>();
    follower = owned.get();
    host.add("follower", "follower", std::move(owned));
    host.configure("follower");
    host.add("planner", "planner", std::make_unique<TargetPlanner>());
    host.configure("planner");
    host.chain("follower", "target", "planner", "target");
    host.add("hold", "hold", wbi::controllers::make_hold_controller());
    host.configure("hold");
    EXPECT_TRUE(host.references("follower").empty()) << "a chained input reads no topic";
    host.set_initial("follower");  // its planner comes with it
  });
  arm.run(1500);
  EXPECT_EQ(arm.host().active(), "planner, follower");
  // Every tick's point was the state's own (max_age_s is half a tick): no tick of delay.
  EXPECT_EQ(follower->fresh(), 1500);
  EXPECT_LT(arm.error_to_target(), 0.05);
  // Deactivating the follower takes its planner along; hold takes the joints.
  auto request =
      std::async(std::launch::async, [&] { return arm.host().request_switch({}, {"follower"}); });
  const auto result = arm.tick_until(request);
  ASSERT_TRUE(result.done) << result.text;
  EXPECT_EQ(arm.host().active(), "hold");
}

TEST(ControllerHostChaining, BadChainsAreRefusedNamingWhy) {
  HostedArm arm("host_chain_bad", 1.0, [&](ControllerHost& host) {
    host.add("follower", "follower", std::make_unique<FollowerPd>());
    host.add("planner", "planner", std::make_unique<TargetPlanner>());
    const auto refusal = [&](auto&& call) {
      try {
        call();
      } catch (const wbi::Error& e) {
        return std::string(e.what());
      }
      return std::string("accepted");
    };
    EXPECT_EQ(refusal([&] { host.chain("follower", "goal", "planner", "target"); }),
              "controller 'follower' has no reference input 'goal' (target)");
    EXPECT_EQ(refusal([&] { host.chain("follower", "target", "planner", "com"); }),
              "controller 'planner' has no reference output 'com' (target)");
    EXPECT_EQ(refusal([&] { host.chain("follower", "target", "follower", "target"); }),
              "controller 'follower' has no reference output 'target' (none)");
    host.chain("follower", "target", "planner", "target");
    EXPECT_EQ(refusal([&] { host.chain("follower", "target", "planner", "target"); }),
              "the reference input follower/target is chained already");
    host.add("hold", "hold", wbi::controllers::make_hold_controller());
    host.configure("hold");
    host.set_initial("hold");
  });
}

}  // namespace
