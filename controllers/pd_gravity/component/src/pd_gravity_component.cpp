#include "wbi/controllers/pd_gravity_component.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include <wbi/controllers/pd_gravity.hpp>
#include <wbi/dds_interface.hpp>
#include <wbi/runtime/producer_counters.hpp>

namespace wbi::controllers {

namespace {

Eigen::VectorXd to_vector(const std::vector<double>& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

class PdGravityComponent final : public runtime::Component {
 public:
  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    DdsInterfaceOptions options;
    options.robot = parameters.require<std::string>("robot");
    const std::string model = parameters.get<std::string>("model", "local");
    if (model != "local" && model != "remote") {
      throw runtime::ParameterError(parameters.where("model") + ": model is '" + model +
                                    "'; expected local or remote");
    }
    options.model_source = model == "remote" ? DdsInterfaceOptions::ModelSource::remote
                                             : DdsInterfaceOptions::ModelSource::local;
    // A local model needs the URDF; a remote one uses it only for frame names.
    std::filesystem::path urdf = model == "local" ? parameters.require<std::string>("urdf")
                                                  : parameters.get<std::string>("urdf", "");
    if (!urdf.empty() && urdf.is_relative() && !parameters.file().empty() &&
        parameters.file() != "<string>") {
      urdf = std::filesystem::path(parameters.file()).parent_path() / urdf;
    }
    options.urdf = urdf.string();
    options.local_model_backend = parameters.get<std::string>("model_backend", "wbi");
    options.model_timeout = std::chrono::milliseconds(
        static_cast<std::int64_t>(parameters.get<double>("model_timeout_s", 0.2) * 1000));
    options.controller = parameters.get<std::string>("controller", context.instance);
    const auto claim = parameters.get<std::string>("claim", "claim");
    if (const auto parsed = claim_from_text(claim)) {
      options.claim = *parsed;
    } else {
      throw runtime::ParameterError(parameters.where("claim") + ": claim is '" + claim +
                                    "': expected claim, force or none");
    }
    options.max_age_s = parameters.get<double>("max_age_s", 0.05);
    wait_for_state_ = parameters.get<bool>("wait_for_state", false);
    // A cycle waits at most this long for the next estimate (then: a stale cycle).
    options.blocking_read_timeout = std::chrono::milliseconds(
        static_cast<std::int64_t>(parameters.get<double>("state_timeout_s", 0.005) * 1000));
    // The host's participant: one secured participant per process (see
    // DdsInterfaceOptions::shared_participant).
    options.participant = context.participant->options();
    options.shared_participant = context.participant;
    const auto joints = parameters.require<std::vector<std::string>>("joints");
    const auto target = parameters.require<std::vector<double>>("target");
    const auto kp = parameters.get<std::vector<double>>("kp", {});
    const auto kd = parameters.get<std::vector<double>>("kd", {});
    const double bandwidth_hz = parameters.get<double>("bandwidth_hz", 5.0);
    const double init_timeout_s = parameters.get<double>("init_timeout_s", 30.0);
    progress_period_s_ = parameters.get<double>("progress_period_s", 1.0);
    if (kp.empty() != kd.empty()) {
      throw runtime::ParameterError(parameters.where(kp.empty() ? "kd" : "kp") +
                                    ": give both kp and kd, or neither (gains from bandwidth_hz)");
    }
    if (!(bandwidth_hz > 0.0)) {
      throw runtime::ParameterError(parameters.where("bandwidth_hz") +
                                    ": bandwidth_hz must be > 0, got " +
                                    std::to_string(bandwidth_hz));
    }

    options.on_producer_event = runtime::count_producer_events(report());
    robot_ = make_dds_interface(options);
    robot_->add_joints(joints);
    robot_->init(std::chrono::milliseconds(static_cast<std::int64_t>(init_timeout_s * 1000)));
    const int n = robot_->dofs();
    const auto check = [&](const char* key, std::size_t size) {
      if (size != static_cast<std::size_t>(n)) {
        throw runtime::ParameterError(parameters.where(key) + ": " + key + " has " +
                                      std::to_string(size) + " values for " + std::to_string(n) +
                                      " controlled joints");
      }
    };
    check("target", target.size());
    PdGravityGains gains;
    if (!kp.empty()) {
      check("kp", kp.size());
      check("kd", kd.size());
      gains = PdGravityGains::diagonal(to_vector(kp), to_vector(kd));
    } else {
      // Every mode critically damped at bandwidth_hz, from the inertia at the target.
      Eigen::MatrixXd M(6 + n, 6 + n);
      robot_->mass_matrix(to_vector(target), Transform::Identity(), M);
      gains = PdGravityGains::from_inertia(M.bottomRightCorner(n, n), bandwidth_hz);
    }
    controller_.emplace(*robot_, gains, to_vector(target));
    newest_q_.setZero(n);
  }

  void on_activate() override {
    controller_->start();
    start_ns_ = -1;
  }

  // wait_for_state: each cycle starts when a new estimate arrives (the runner's
  // event), so the command follows its sensor sample by one pipeline pass.
  bool event_driven() const override { return wait_for_state_; }
  bool wait_for_event(std::int64_t /*timeout_ns*/) override {
    try {
      robot_->read_estimates(EstimateKind::joint_position, newest_q_, ReadMode::blocking);
      return true;
    } catch (const TimeoutError&) {
      ++stale_;  // no new estimate within state_timeout_s
    } catch (const StaleDataError&) {
      ++stale_;
    }
    return false;
  }

  void update(std::int64_t time_ns, std::int64_t /*period_ns*/) override {
    try {
      controller_->update(ReadMode::latest);
    } catch (const StaleDataError&) {
      ++stale_;  // no fresh state this cycle: no command; the robot's watchdog guards
      return;
    }
    if (start_ns_ < 0) {
      start_ns_ = time_ns;
      next_progress_ns_ = time_ns;
    }
    if (progress_period_s_ > 0 && time_ns >= next_progress_ns_) {
      next_progress_ns_ += static_cast<std::int64_t>(progress_period_s_ * 1e9);
      std::printf("t = %6.2f s  max joint error %.4f rad\n",
                  1e-9 * static_cast<double>(time_ns - start_ns_), controller_->max_error());
      std::fflush(stdout);
    }
  }

  void on_shutdown() override {
    if (controller_) {
      std::printf("stale cycles: %llu\nfinal max joint error: %.9g rad\n",
                  static_cast<unsigned long long>(stale_), controller_->max_error());
      std::fflush(stdout);
    }
    controller_.reset();
    if (robot_) {
      robot_->close();
    }
  }

 private:
  std::unique_ptr<WholeBodyInterface> robot_;
  std::optional<PdGravity> controller_;
  double progress_period_s_ = 1.0;
  bool wait_for_state_ = false;
  Eigen::VectorXd newest_q_;  // wait_for_event's read (the cycle reads the same sample again)
  std::int64_t start_ns_ = -1;
  std::int64_t next_progress_ns_ = 0;
  std::uint64_t stale_ = 0;
};

}  // namespace

void register_components(runtime::Registry& registry) {
  registry.add<PdGravityComponent>(
      "pd_gravity", "PD + gravity compensation through the DDS whole-body interface");
}

}  // namespace wbi::controllers
