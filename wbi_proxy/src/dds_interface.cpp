// DdsInterface: the whole-body interface over the robot's DDS topics, composed
// of one object per element (dds_actuators, dds_sensors, dds_state, and a
// local_model or remote_model) over one shared RobotConnection. It owns the
// lifecycle (add_joints, init, close) and hands out the elements; it forwards
// no element call.
#include "wbi/dds_interface.hpp"

#include <memory>

#include "dds_actuators.hpp"
#include "dds_sensors.hpp"
#include "dds_state.hpp"
#include "local_model.hpp"
#include "remote_model.hpp"
#include "robot_connection.hpp"

namespace wbi::proxy {

namespace {

class DdsInterface final : public WholeBodyInterface {
 public:
  explicit DdsInterface(const DdsInterfaceOptions& options)
      : robot_(options), actuators_(robot_), sensors_(robot_), state_(robot_) {
    if (options.model_source == DdsInterfaceOptions::ModelSource::remote) {
      auto remote = std::make_unique<RemoteModel>(robot_.participant, options);
      remote_ = remote.get();
      model_ = std::move(remote);
    }
  }

  void add_joints(const IdList& joints) override {
    if (robot_.initialized) {
      throw Error("add_joints() after init(): the controlled joints are fixed by then");
    }
    for (const auto& joint : joints) {
      for (const auto& known : controlled_) {
        if (known == joint) {
          throw Error("joint '" + joint + "' added twice");
        }
      }
      controlled_.push_back(joint);
    }
  }

  void init(std::chrono::milliseconds timeout) override {
    if (robot_.initialized) {
      throw Error("init() called twice");
    }
    if (controlled_.empty()) {
      throw Error("no controlled joints: call add_joints() before init()");
    }
    wait_for_robot(timeout);
    robot_.resolve(controlled_);
    const auto& options = robot_.options;
    if (remote_ != nullptr) {
      remote_->bind(controlled_, robot_.locked_positions());
    } else {
      model_ = std::make_unique<LocalModel>(options.urdf, controlled_, robot_.locked_positions(),
                                            options.local_model_backend, options.armature);
    }
    state_.use_frames_of(*model_);
    actuators_.prepare();
    actuators_.claim(timeout);  // before any command
    robot_.initialized = true;
  }

  void close() override {
    robot_.initialized = false;
    actuators_.release();
  }

  const IdList& joint_list() const override { return controlled_; }

  void set_state_callback(std::function<void()> on_state) {
    if (!on_state) {
      robot_.state.subscriber.set_callback(nullptr);
      return;
    }
    robot_.state.subscriber.set_callback(
        [on_state = std::move(on_state)](const wbi::msg::StateEstimate&,
                                         const dds::detail::SampleInfo&) { on_state(); });
  }

  bool lockstep() const {
    robot_.require_init();
    return robot_.lockstep();
  }

  Actuators& actuators() override {
    robot_.require_init();
    return actuators_;
  }
  Sensors& sensors() override {
    robot_.require_init();
    return sensors_;
  }
  const Sensors& sensors() const override {
    robot_.require_init();
    return sensors_;
  }
  State& state() override {
    robot_.require_init();
    return state_;
  }
  const State& state() const override {
    robot_.require_init();
    return state_;
  }
  Model& model() override {
    robot_.require_init();  // before it, a local model does not exist yet
    return *model_;
  }
  const Model& model() const override {
    robot_.require_init();
    return *model_;
  }

 private:
  // Waits for every component the interface needs; names all that are missing.
  void wait_for_robot(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::vector<std::string> missing;
    robot_.wait(deadline, missing);
    actuators_.wait(deadline, missing);
    if (remote_ != nullptr) {
      const std::string model_missing = remote_->wait_ready(deadline);
      if (!model_missing.empty()) {
        missing.push_back(model_missing);
      }
    }
    if (!missing.empty()) {
      std::string text = "robot '" + robot_.options.robot + "' not ready within " +
                         seconds_text(std::chrono::duration<double>(timeout).count()) +
                         "; missing: ";
      for (std::size_t i = 0; i < missing.size(); ++i) {
        text += (i == 0 ? "" : "; ") + missing[i];
      }
      throw TimeoutError(text);
    }
  }

  RobotConnection robot_;
  IdList controlled_;
  DdsActuators actuators_;
  DdsSensors sensors_;
  DdsState state_;
  std::unique_ptr<wbi::Model> model_;  // LocalModel from init(), or RemoteModel from
                                       // construction on (DdsInterfaceOptions::model_source)
  RemoteModel* remote_ = nullptr;      // model_ when the model is remote
};

}  // namespace

}  // namespace wbi::proxy

namespace wbi {

std::optional<DdsInterfaceOptions::Claim> claim_from_text(std::string_view text) {
  using Claim = DdsInterfaceOptions::Claim;
  if (text == "claim") {
    return Claim::claim;
  }
  if (text == "force") {
    return Claim::force;
  }
  if (text == "none") {
    return Claim::none;
  }
  return std::nullopt;
}

std::unique_ptr<WholeBodyInterface> make_dds_interface(const DdsInterfaceOptions& options) {
  if (options.robot.empty()) {
    throw Error("DdsInterfaceOptions.robot is empty: name the robot whose topics to use");
  }
  if (options.model_source == DdsInterfaceOptions::ModelSource::local && options.urdf.empty()) {
    throw Error("DdsInterfaceOptions.urdf is empty: a local model needs the robot's URDF");
  }
  if (options.model_source == DdsInterfaceOptions::ModelSource::remote &&
      options.model_timeout.count() <= 0) {
    throw Error("DdsInterfaceOptions.model_timeout must be > 0 for a remote model");
  }
  if (!(options.max_age_s > 0.0)) {
    throw Error("DdsInterfaceOptions.max_age_s must be > 0");
  }
  return std::make_unique<proxy::DdsInterface>(options);
}

void set_state_callback(WholeBodyInterface& interface, std::function<void()> on_state) {
  auto* dds_interface = dynamic_cast<proxy::DdsInterface*>(&interface);
  if (dds_interface == nullptr) {
    throw Error("set_state_callback: not an interface from make_dds_interface");
  }
  dds_interface->set_state_callback(std::move(on_state));
}

bool robot_in_lockstep(const WholeBodyInterface& interface) {
  const auto* dds_interface = dynamic_cast<const proxy::DdsInterface*>(&interface);
  if (dds_interface == nullptr) {
    throw Error("robot_in_lockstep: not an interface from make_dds_interface");
  }
  return dds_interface->lockstep();
}

}  // namespace wbi
