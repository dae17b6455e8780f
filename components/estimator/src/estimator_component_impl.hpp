// Private to the estimator component: the EstimatorComponent class (its inputs,
// estimators and state), whose parts are estimator_component*.cpp.
#pragma once

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Core>
#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/estimation/estimator_factory.hpp>
#include <wbi/estimation/low_pass_filter.hpp>
#include <wbi/estimation/model_kalman.hpp>
#include <wbi/runtime/duration_histogram.hpp>

#include "accelerations_from_model.hpp"
#include "torques_from_force_torque.hpp"
#include "wbi/estimator/base_estimator.hpp"
#include "wbi/estimator/estimator_component.hpp"
#include "wbi/estimator/legged_base_estimator.hpp"

namespace wbi::estimator::detail {

enum class BaseSource { fixed, fixed_link, legged, topic };

class EstimatorComponent final : public runtime::Component {
 public:
  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override;
  void on_activate() override;
  void on_deactivate() override;
  void on_cleanup() override;
  void on_shutdown() override { on_cleanup(); }

 private:
  void configure_legged(const runtime::Parameters& parameters);
  void configure_model_accelerations(const runtime::Parameters& parameters,
                                     const std::string& urdf);
  void prepare_legged(const wbi::msg::RobotDescription& description,
                      const std::vector<std::string>& joints);
  bool prepare(std::size_t joints);
  bool prepare_sized(std::size_t joints);
  void on_description();
  void on_base_sample(std::uint64_t seq);
  void on_command(const wbi::msg::ActuatorCommand& command);
  // A tick's inputs (estimator_component_sample.cpp, "Inputs of a tick"); caller holds mutex_.
  bool inputs_in(std::uint64_t seq) const;
  void defer(const wbi::msg::SensorSample& sample);
  void estimate_deferred(bool timed_out);
  void run_deferred();  // the deferred sample's deadline, on a thread of its own
  void stop_deferred();
  bool ready(std::size_t joints);
  void process_pending();  // caller holds mutex_
  void on_sample(const wbi::msg::SensorSample& sample, const dds::detail::Guid& writer);
  void on_new_producer(const dds::detail::Guid& writer);  // caller holds mutex_
  void estimate(const wbi::msg::SensorSample& sample);
  void filter_force_torque(const wbi::msg::SensorSample& sample);
  void fill_state(const wbi::msg::SensorSample& sample);
  void write_base(const BaseState& base);
  bool has_legged_inputs(const wbi::msg::SensorSample& sample) const;
  Eigen::Map<const Eigen::VectorXd> sample_q() const;  // the current sample's encoders
  ImuInput sample_imu() const;
  const Eigen::Matrix3Xd& foot_forces();
  void fill_base(const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq);
  void estimate_torques(const Eigen::VectorXd& dq, const Eigen::VectorXd& ddq);
  void feed_model_acceleration();
  estimation::StreamParameters estimator_stream() const;
  void prepare_model_acceleration(const wbi::msg::RobotDescription& description,
                                  const std::vector<std::string>& joints);
  void on_parameter(const wbi::msg::EstimatorParameter& parameter);
  void apply_parameter(const wbi::msg::EstimatorParameter& parameter);

  std::string robot_;
  std::string method_;
  estimation::Parameters method_parameters_;
  double cutoff_hz_ = 0.0;
  BaseSource base_source_ = BaseSource::fixed;
  std::string urdf_;
  std::string fixed_link_;
  Eigen::Matrix4d base_pose_ = Eigen::Matrix4d::Identity();

  std::atomic<bool> active_{false};
  // Between the sample, command, parameter and ground-truth callbacks and the
  // deferred thread. Recursive: the state is published under it, and in one
  // process Fast DDS delivers on the writer's thread, so a controller that
  // answers the state on that thread (ControllerHostComponent) has its
  // command arrive in on_command, nested in that publish. The estimate is
  // complete by then (the publish is estimate()'s last step).
  std::recursive_mutex mutex_;
  // Sample in to state ready (the DDS write not included), for the end-of-run
  // line (a lockstep run's breakdown): since the last activation.
  runtime::DurationHistogram estimate_times_;
  std::unique_ptr<estimation::DerivativeEstimator> estimator_;
  std::optional<estimation::LowPassFilter> torque_filter_;
  std::optional<estimation::LowPassFilter> force_torque_filter_;  // 6 per F/T sensor; none: no F/T
  Eigen::VectorXd wrenches_;  // [6 m] the sample's F/T readings (force, torque)
  std::unique_ptr<FixedLinkBaseEstimator> base_estimator_;
  std::unique_ptr<LeggedBaseEstimator> legged_estimator_;
  LeggedBaseOptions legged_options_;
  std::string imu_sensor_;  // base: legged; empty: the first IMU
  // base: legged; each foot's F/T sensors (none: unmeasured feet)
  std::array<std::vector<std::string>, 2> foot_sensors_;
  int imu_index_ = -1;                  // among the sample's IMU readings
  std::vector<int> foot_sensor_index_;  // among the sample's F/T readings, the left foot's first
  Eigen::Matrix3Xd foot_forces_;        // their forces, one column each
  int needed_force_torques_ = 0;        // F/T readings a sample must have for them
  // The sample being estimated, from its checks to its publish: its joint
  // positions are read where it holds them (sample_q), not copied.
  const wbi::msg::SensorSample* current_sample_ = nullptr;
  bool have_base_sample_ = false;                  // base: topic
  bool failed_ = false;                            // the description did not fit the base estimator
  std::optional<wbi::msg::SensorSample> pending_;  // a sample that came before the description
  std::size_t joints_ = 0;                         // the description's, once prepared
  Eigen::VectorXd tau_;
  // joint_torques: force_torque (absent: the sensed torques)
  std::optional<TorqueEstimationConfig> torque_config_;
  std::unique_ptr<TorquesFromForceTorque> torque_estimation_;
  // Joint torques fed to torque_filter_: the sample's where the joint has a
  // sensor, 0 where it has none (its NaN never reaches the estimate).
  Eigen::VectorXd tau_in_;
  std::vector<bool> torque_sensor_;  // [joints] from the description
  // accelerations: model — the model's accelerations from the torque commands,
  // fused with the encoders by a filter of their own (the method keeps dq)
  std::string model_urdf_;  // empty: accelerations: method
  std::map<std::string, double> joint_armature_, joint_damping_, joint_friction_;
  double stick_velocity_ = estimation::JointLosses{}.stick_velocity;
  estimation::ModelKalmanParameters model_kalman_;
  std::unique_ptr<AccelerationsFromModel> model_acceleration_;
  std::unique_ptr<estimation::ModelKalmanEstimator> model_ddq_;
  Eigen::VectorXd ddq_model_;
  bool sample_used_ = false;  // the last sample entered the joint estimator
  std::uint32_t ignored_ = 0;
  runtime::StatusCounter* dropped_ = nullptr;  // the report's counters (on_configure)
  runtime::StatusCounter* duplicated_ = nullptr;
  runtime::StatusCounter* out_of_order_ = nullptr;
  runtime::StatusCounter* gaps_ = nullptr;
  runtime::StatusCounter* non_finite_ = nullptr;
  runtime::StatusCounter* wrong_size_ = nullptr;
  runtime::StatusCounter* new_producers_ = nullptr;
  runtime::StatusCounter* invalid_torque_estimates_ = nullptr;  // samples with some invalid
  runtime::StatusCounter* missing_force_torque_ = nullptr;      // samples without every F/T reading
  runtime::StatusCounter* without_model_acceleration_ = nullptr;  // a joint without a torque
  dds::detail::Guid producer_{};              // the writer of the last sensor sample
  estimation::StampCounters earlier_counts_;  // of the filters before a new producer
  wbi::msg::StateEstimate state_;
  dds::Received<wbi::msg::GroundTruth> ground_truth_rx_;
  // Inputs of a tick: the robot's ground truth of the same tick (base: topic on
  // the robot's own ground truth), the lockstep controllers' commands of the
  // tick before (accelerations: model with lockstep_controllers). A sample
  // whose inputs have not all come waits in deferred_ (at most inputs_timeout_).
  bool match_ground_truth_ = false;
  std::int64_t ground_truth_seq_ = -1;  // of the newest base sample
  bool ground_truth_waived_ = false;    // not waited for until its next sample
  std::vector<std::string> lockstep_controllers_;
  std::vector<std::int64_t> answered_;  // per lockstep controller, its newest command's tick
  std::vector<char> waived_;            // per lockstep controller: not waited for until it answers
  std::chrono::nanoseconds inputs_timeout_{0};
  wbi::msg::SensorSample deferred_;
  bool has_deferred_ = false;
  std::chrono::steady_clock::time_point deferred_until_;
  std::condition_variable_any deferred_changed_;
  bool stopping_ = false;
  std::thread deferred_thread_;
  runtime::StatusCounter* late_inputs_ = nullptr;  // samples estimated after inputs_timeout_

  std::unique_ptr<dds::Subscriber<wbi::msg::RobotDescription>> description_;
  std::unique_ptr<dds::Publisher<wbi::msg::StateEstimate>> state_publisher_;
  std::unique_ptr<dds::Subscriber<wbi::msg::GroundTruth>> ground_truth_;
  std::unique_ptr<dds::Subscriber<wbi::msg::EstimatorParameter>> parameter_subscriber_;
  std::unique_ptr<dds::Subscriber<wbi::msg::ActuatorCommand>> commands_;  // accelerations: model
  std::unique_ptr<dds::Subscriber<wbi::msg::SensorSample>> sensors_;
};

}  // namespace wbi::estimator::detail
