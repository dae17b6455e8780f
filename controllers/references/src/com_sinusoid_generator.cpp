// The `com_sinusoid` component: the balancing experiments' CoM reference
// (com_sinusoid.hpp) on wbi/<robot>/references/<controller>/<input>, one
// point per state the robot's estimator publishes.
//
// It reads the state like a controller, but claims no joint. While settling,
// the point is the CoM of that state (the balancer then holds the measured
// CoM); afterwards the sinusoid, whose points it also sends one state ahead
// (at the stamp one period on), so that a controller in lockstep rarely waits
// for it. Its time starts at the first state it reads: in lockstep the
// controller host waits for this generator's first point before its first
// tick (reference_wait_s), so that both start at the same state.
#include <algorithm>
#include <cstdio>
#include <optional>

#include <wbi/controllers/com_measures.hpp>
#include <wbi/controllers/com_sinusoid.hpp>
#include <wbi/controllers/interface_options.hpp>
#include <wbi/controllers/reference_generators.hpp>
#include <wbi/controllers/reference_writer.hpp>
#include <wbi/dds_interface.hpp>

namespace wbi::controllers {

namespace {

class ComSinusoidGenerator final : public runtime::Component {
 public:
  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    DdsInterfaceOptions options = read_interface_options(parameters, context);
    options.claim = DdsInterfaceOptions::Claim::none;  // it reads, it never commands
    options.blocking_read_timeout = std::chrono::milliseconds(
        static_cast<std::int64_t>(parameters.get<double>("state_timeout_s", 0.005) * 1000));
    read_sinusoid(parameters);
    configured_ = sinusoid_;
    const auto joints = parameters.require<std::vector<std::string>>("joints");
    const std::string controller = parameters.require<std::string>("controller");
    const std::string input = parameters.get<std::string>("input", "com");
    robot_ = make_dds_interface(options);
    robot_->add_joints(joints);
    robot_->init(std::chrono::milliseconds(
        static_cast<std::int64_t>(parameters.get<double>("init_timeout_s", 30.0) * 1000)));
    try {
      left_ = robot_->frame_index(parameters.get<std::string>("left_sole", "l_sole"));
      right_ = robot_->frame_index(parameters.get<std::string>("right_sole", "r_sole"));
    } catch (const Error& e) {
      throw runtime::ParameterError(parameters.where() + ": " + e.what());
    }
    state_ = RobotState(robot_->dofs());
    writer_.emplace(*context.participant, options.robot, controller, input, context.instance);
  }

  bool event_driven() const override { return true; }
  bool wait_for_event(std::int64_t /*timeout_ns*/) override {
    try {
      robot_->state().read_robot_state(state_, ReadMode::blocking);
      return true;
    } catch (const TimeoutError&) {
    } catch (const StaleDataError&) {
    }
    return false;
  }

  void update(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) override {
    const std::int64_t stamp = state_.stamp.source_ns;
    if (stamp == last_state_ns_) {
      return;  // answered already
    }
    if (stamp < last_state_ns_) {
      // The robot's time went back: a new simulation. Its experiment starts
      // over: settling on the robot as it stands, then the sinusoid.
      std::printf(
          "com_sinusoid: the robot's time went back to %.3f s (a new robot?): the "
          "reference starts over\n",
          1e-9 * static_cast<double>(stamp));
      std::fflush(stdout);
      sinusoid_ = configured_;
      start_ns_ = last_state_ns_ = last_sent_ns_ = -1;
      step_ns_ = 0;
    }
    if (last_state_ns_ >= 0) {
      // The robot's period: the smallest step seen (a late read skips states).
      const std::int64_t step = stamp - last_state_ns_;
      step_ns_ = step_ns_ > 0 ? std::min(step_ns_, step) : step;
    }
    last_state_ns_ = stamp;
    if (start_ns_ < 0) {
      start_ns_ = stamp;
    }
    const auto since_start = [&](std::int64_t ns) {
      return 1e-9 * static_cast<double>(ns - start_ns_);
    };
    sinusoid_.follow(
        since_start(stamp), [&] { return com(); }, [&] { return feet_center(); });
    if (stamp > last_sent_ns_) {
      send(stamp, since_start(stamp));
    }
    // Once anchored the sinusoid is known ahead: every state's point up to
    // the next one's, now (a few at most, within the writer's history).
    if (step_ns_ > 0 && !sinusoid_.settling(since_start(stamp))) {
      for (int ahead = 0; ahead < 4 && last_sent_ns_ + step_ns_ <= stamp + step_ns_; ++ahead) {
        send(last_sent_ns_ + step_ns_, since_start(last_sent_ns_ + step_ns_));
      }
    }
  }

  void on_shutdown() override {
    writer_.reset();
    if (robot_) {
      robot_->close();
    }
  }

 private:
  void read_sinusoid(const runtime::Parameters& parameters) {
    sinusoid_.amplitude = parameters.get<double>("amplitude", sinusoid_.amplitude);
    sinusoid_.frequency_hz = parameters.get<double>("frequency_hz", sinusoid_.frequency_hz);
    sinusoid_.settle_s = parameters.get<double>("settle_s", sinusoid_.settle_s);
    const auto d = parameters.get<std::vector<double>>("direction", {0.0, 1.0, 0.0});
    if (d.size() != 3 || Eigen::Vector3d(d[0], d[1], d[2]).norm() == 0.0) {
      throw runtime::ParameterError(parameters.where("direction") +
                                    ": direction takes 3 values, not all zero");
    }
    sinusoid_.direction = Eigen::Vector3d(d[0], d[1], d[2]).normalized();
    if (!(sinusoid_.amplitude >= 0.0) || !(sinusoid_.frequency_hz >= 0.0) ||
        !(sinusoid_.settle_s >= 0.0)) {
      throw runtime::ParameterError(parameters.where() +
                                    ": amplitude, frequency_hz and settle_s must be >= 0");
    }
  }

  Eigen::Vector3d com() { return measured_com(*robot_, state_); }
  Eigen::Vector3d feet_center() {
    return controllers::feet_center(*robot_, state_, left_, right_, sole_pose_);
  }

  void send(std::int64_t stamp_ns, double t) {
    Eigen::Vector3d x, v, a;
    sinusoid_.at(t, x, v, a);
    writer_->write(stamp_ns, {x.data(), 3}, {v.data(), 3}, {a.data(), 3});
    last_sent_ns_ = stamp_ns;
  }

  std::unique_ptr<WholeBodyInterface> robot_;
  RobotState state_;
  ComSinusoid sinusoid_, configured_;  // configured_: as it starts
  int left_ = -1, right_ = -1;
  Transform sole_pose_ = Transform::Identity();
  std::int64_t start_ns_ = -1, last_state_ns_ = -1, last_sent_ns_ = -1, step_ns_ = 0;
  std::optional<ReferenceWriter> writer_;
};

}  // namespace

void register_reference_generators(runtime::Registry& registry) {
  registry.add(
      "com_sinusoid", [] { return std::make_unique<ComSinusoidGenerator>(); },
      "a CoM reference for a balancer: the measured CoM while settling, then a sinusoid "
      "between the feet (wbi/<robot>/references/<controller>/<input>)");
}

}  // namespace wbi::controllers
