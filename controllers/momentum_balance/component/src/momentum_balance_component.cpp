#include "wbi/controllers/momentum_balance_component.hpp"

#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <wbi/controllers/com_sinusoid.hpp>
#include <wbi/controllers/momentum_balance.hpp>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/runtime/process_exit.hpp>
#include <wbi/runtime/producer_counters.hpp>

namespace wbi::controllers {

namespace {

Eigen::VectorXd to_vector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

MomentumBalanceParameters read_parameters(const runtime::Parameters& parameters) {
  MomentumBalanceParameters p;
  p.left_sole = parameters.get<std::string>("left_sole", p.left_sole);
  p.right_sole = parameters.get<std::string>("right_sole", p.right_sole);
  p.foot_x_min = parameters.get<double>("foot_x_min", p.foot_x_min);
  p.foot_x_max = parameters.get<double>("foot_x_max", p.foot_x_max);
  p.foot_y_min = parameters.get<double>("foot_y_min", p.foot_y_min);
  p.foot_y_max = parameters.get<double>("foot_y_max", p.foot_y_max);
  p.friction = parameters.get<double>("friction", p.friction);
  p.torsional_friction = parameters.get<double>("torsional_friction", p.torsional_friction);
  p.min_normal_force = parameters.get<double>("min_normal_force", p.min_normal_force);
  p.com_kp = parameters.get<double>("com_kp", p.com_kp);
  p.com_kd = parameters.get<double>("com_kd", p.com_kd);
  p.angular_momentum_kd = parameters.get<double>("angular_momentum_kd", p.angular_momentum_kd);
  p.posture_bandwidth_hz = parameters.get<double>("posture_bandwidth_hz", p.posture_bandwidth_hz);
  p.torque_weight = parameters.get<double>("torque_weight", p.torque_weight);
  p.wrench_weight = parameters.get<double>("wrench_weight", p.wrench_weight);
  p.foot_moment_weight = parameters.get<double>("foot_moment_weight", p.foot_moment_weight);
  return p;
}

// What the signals topic carries, in this order.
constexpr std::array kSignalNames = {"com_x",     "com_y",     "com_z",    "com_ref_x", "com_ref_y",
                                     "com_ref_z", "com_error", "left_f_z", "right_f_z"};

class MomentumBalanceComponent final : public runtime::Component {
 public:
  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    new_estimators_ = &report().counter("new_estimators");
    DdsInterfaceOptions options;
    options.robot = parameters.require<std::string>("robot");
    std::filesystem::path urdf = parameters.require<std::string>("urdf");
    if (urdf.is_relative() && !parameters.file().empty() && parameters.file() != "<string>") {
      urdf = std::filesystem::path(parameters.file()).parent_path() / urdf;
    }
    options.urdf = urdf.string();
    options.local_model_backend = parameters.get<std::string>("model_backend", "wbi");
    options.controller = parameters.get<std::string>("controller", context.instance);
    options.max_age_s = parameters.get<double>("max_age_s", 0.05);
    // The host's participant: one secured participant per process (see
    // DdsInterfaceOptions::shared_participant).
    options.participant = context.participant->options();
    options.shared_participant = context.participant;
    const auto joints = parameters.require<std::vector<std::string>>("joints");
    const auto posture = parameters.get<std::vector<double>>("posture", {});
    reference_.amplitude = parameters.get<double>("com_amplitude", 0.05);
    reference_.frequency_hz = parameters.get<double>("com_frequency_hz", 0.2);
    const auto direction = parameters.get<std::vector<double>>("com_direction", {0.0, 1.0, 0.0});
    reference_.settle_s = parameters.get<double>("settle_s", 0.5);
    const double init_timeout_s = parameters.get<double>("init_timeout_s", 30.0);
    progress_period_s_ = parameters.get<double>("progress_period_s", 1.0);
    exit_after_s_ = parameters.get<double>("exit_after_s", 0.0);
    if (direction.size() != 3 || Eigen::Vector3d(direction.data()).norm() == 0.0) {
      throw runtime::ParameterError(parameters.where("com_direction") +
                                    ": com_direction must be 3 numbers, not all zero");
    }
    reference_.direction = Eigen::Vector3d(direction.data()).normalized();
    const MomentumBalanceParameters balance = read_parameters(parameters);
    if (parameters.get<bool>("signals", true)) {
      signals_publisher_ = std::make_unique<dds::Publisher<wbi::msg::Signals>>(
          *context.participant, dds::topics::signals(options.robot, context.instance),
          dds::qos::kStream);
      signals_.header().robot(options.robot);
      signals_.source(context.instance);
      for (const auto& name : kSignalNames) {
        signals_.names().emplace_back(name);
      }
      signals_.values(std::vector<double>(kSignalNames.size(), 0.0));
    }

    // A new estimator is a rebound of the state stream (wbi/dds/producers.hpp),
    // said before its first sample is taken.
    std::string state_topic = "'";  // as the rebound's line quotes it
    state_topic += dds::topics::state(options.robot);
    state_topic += '\'';
    options.on_producer_event = [count = runtime::count_producer_events(report()),
                                 state = std::move(state_topic),
                                 this](const dds::ProducerEvent& event) {
      count(event);
      if (event.kind == dds::ProducerEvent::Kind::rebound &&
          event.text.find(state) != std::string_view::npos) {
        new_estimator_.store(true);
      }
    };
    robot_ = make_dds_interface(options);
    robot_->add_joints(joints);
    robot_->init(std::chrono::milliseconds(static_cast<std::int64_t>(init_timeout_s * 1000)));
    const int n = robot_->dofs();
    Eigen::VectorXd q_posture(n);
    if (posture.empty()) {
      robot_->read_estimates(EstimateKind::joint_position, q_posture);
    } else if (posture.size() != static_cast<std::size_t>(n)) {
      throw runtime::ParameterError(parameters.where("posture") + ": posture has " +
                                    std::to_string(posture.size()) + " values for " +
                                    std::to_string(n) + " controlled joints");
    } else {
      q_posture = to_vector(posture);
    }
    try {
      controller_.emplace(*robot_, balance, q_posture);
    } catch (const Error& e) {
      throw runtime::ParameterError(parameters.where() + ": " + e.what());
    }
  }

  void on_activate() override {
    controller_->start();
    start_ns_ = -1;
  }

  void update(std::int64_t /*time_ns*/, std::int64_t /*period_ns*/) override {
    Stamp stamp;
    try {
      stamp = controller_->read_state(ReadMode::latest);
    } catch (const StaleDataError&) {
      ++stale_;  // no fresh state this cycle: no command; the robot's watchdog guards
      return;
    }
    if (has_seq_ && stamp.seq == last_seq_) {
      return;  // this estimate was answered already
    }
    if (has_seq_ && new_estimator_.exchange(false)) {
      // A new estimator: its world frame need not be the old one's (a legged
      // base starts at x = y = 0 wherever the robot stands). The reference
      // moves with the CoM's estimate, so that the robot does not (it moved
      // 5 cm to the shifted reference before).
      const Eigen::Vector3d shift = controller_->com_of_state() - controller_->com();
      reference_.origin += shift;
      new_estimators_->add();
      std::printf("new estimator: CoM reference moved with its frame by (%.4f, %.4f, %.4f) m\n",
                  shift.x(), shift.y(), shift.z());
      std::fflush(stdout);
    }
    has_seq_ = true;
    last_seq_ = stamp.seq;
    if (start_ns_ < 0) {
      start_ns_ = stamp.source_ns;
      next_progress_ns_ = stamp.source_ns;
    }
    const double t = 1e-9 * static_cast<double>(stamp.source_ns - start_ns_);
    set_reference(t);
    controller_->control();

    // The run's figures end at exit_after_s: the ticks answered while the
    // process shuts down are not counted (how many depends on timing).
    if (t >= reference_.settle_s && !exit_requested_) {
      const double error = (controller_->com() - controller_->com_reference()).norm();
      squared_error_ += error * error;
      max_error_ = std::max(max_error_, error);
      ++samples_;
    }
    publish_signals(stamp);
    if (exit_after_s_ > 0.0 && t >= exit_after_s_ && !exit_requested_) {
      // The run is over: end the hosting process (wbi_host shuts the components
      // down, so the summary is printed), and `wbi launch` ends with it.
      exit_requested_ = true;
      runtime::request_process_exit(0);
    }
    if (progress_period_s_ > 0 && stamp.source_ns >= next_progress_ns_) {
      next_progress_ns_ += static_cast<std::int64_t>(progress_period_s_ * 1e9);
      const Eigen::Vector3d& c = controller_->com();
      const auto& w = controller_->wrenches();
      std::printf("t = %6.2f s  com (%.4f, %.4f, %.4f) m  error %.4f m  feet f_z %.1f / %.1f N\n",
                  t, c.x(), c.y(), c.z(), (c - controller_->com_reference()).norm(), w[2], w[8]);
      std::fflush(stdout);
    }
  }

  void on_shutdown() override {
    if (controller_) {
      std::printf(
          "stale cycles: %llu\nqp failures: %llu\nmax com error: %.6f m\n"
          "com tracking rms: %.6f m\n",
          static_cast<unsigned long long>(stale_),
          static_cast<unsigned long long>(controller_->qp_failures()), max_error_,
          samples_ > 0 ? std::sqrt(squared_error_ / static_cast<double>(samples_)) : 0.0);
      std::fflush(stdout);
    }
    controller_.reset();
    signals_publisher_.reset();
    if (robot_) {
      robot_->close();
    }
  }

 private:
  void publish_signals(const Stamp& stamp) {
    if (!signals_publisher_) {
      return;
    }
    const Eigen::Vector3d& c = controller_->com();
    const Eigen::Vector3d& r = controller_->com_reference();
    const auto& w = controller_->wrenches();
    auto& v = signals_.values();  // sized at configure: filled in place
    v[0] = c.x(), v[1] = c.y(), v[2] = c.z();
    v[3] = r.x(), v[4] = r.y(), v[5] = r.z();
    v[6] = (c - r).norm();
    v[7] = w[2], v[8] = w[8];
    signals_.header().stamp_ns(stamp.source_ns);
    signals_.header().seq(signals_seq_++);
    signals_publisher_->publish(signals_);
  }

  void set_reference(double t) {
    reference_.follow(
        t, [&] { return controller_->com_of_state(); },
        [&] { return controller_->feet_center_of_state(); });
    Eigen::Vector3d x, v, a;
    reference_.at(t, x, v, a);
    controller_->set_com_reference(x, v, a);
  }

  std::unique_ptr<WholeBodyInterface> robot_;
  std::optional<MomentumBalance> controller_;
  ComSinusoid reference_;
  double progress_period_s_ = 1.0;
  double exit_after_s_ = 0.0;
  bool exit_requested_ = false;
  std::int64_t start_ns_ = -1;
  std::int64_t next_progress_ns_ = 0;
  std::uint64_t last_seq_ = 0;
  bool has_seq_ = false;
  std::uint64_t stale_ = 0;
  runtime::StatusCounter* new_estimators_ = nullptr;  // status counter "new_estimators"
  std::atomic<bool> new_estimator_{false};            // set on a DDS thread
  double squared_error_ = 0.0, max_error_ = 0.0;
  std::uint64_t samples_ = 0;
  std::unique_ptr<dds::Publisher<wbi::msg::Signals>> signals_publisher_;
  wbi::msg::Signals signals_;
  std::uint64_t signals_seq_ = 0;
};

}  // namespace

void register_momentum_balance(runtime::Registry& registry) {
  registry.add<MomentumBalanceComponent>(
      "momentum_balance",
      "momentum-based balancing on two feet through the DDS whole-body interface");
}

}  // namespace wbi::controllers
