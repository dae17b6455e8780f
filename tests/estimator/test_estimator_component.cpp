// The estimator component over real DDS: one state estimate per sensor
// sample, with its stamp; velocities of a ramp; the fixed-link base estimate
// keeps the chosen link still in the world, and the link can be switched at
// run time; bad parameters are named.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include <wbi/dds/publisher.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/estimation/estimator_factory.hpp>
#include <wbi/estimator/estimator_component.hpp>
#include <wbi/model/algorithms.hpp>
#include <wbi/msg/wire_vocabulary.hpp>
#include <wbi/runtime/runner.hpp>

#include "test_support.hpp"
#include "wrench_reference.hpp"

namespace {

using namespace std::chrono_literals;
namespace topics = wbi::dds::topics;
namespace qos = wbi::dds::qos;

// A robot's description and sensor stream, and the estimator's output, on one participant.
class EstimatorFixture {
 public:
  // force_torque_sensors: F/T sensors "ft_0", … in the description; the samples
  // carry the wrenches of set_wrenches() (or set_readings()), with the frames
  // force_torque_frames (default: none). torque_sensors: the joints listed as
  // JOINT_TORQUE sensors (none listed: every joint has one); the samples carry
  // the joint torques of set_torques(). floating_base: the description's.
  // imu: an IMU "imu" in the description; the samples carry set_imu()'s reading.
  EstimatorFixture(const std::string& robot, const std::vector<std::string>& joints,
                   const std::string& parameters_yaml, int force_torque_sensors = 0,
                   const std::vector<std::string>& torque_sensors = {},
                   const std::vector<std::string>& force_torque_frames = {},
                   bool floating_base = false, bool imu = false)
      : robot_(robot),
        description_(participant_, topics::description(robot), qos::kLatched),
        sensors_(participant_, topics::sensors(robot), qos::kStream),
        parameters_(participant_, topics::estimator_parameters(robot), qos::kCommand),
        state_(participant_, topics::state(robot), qos::kStream) {
    wbi::msg::RobotDescription description;
    description.header().robot(robot);
    description.floating_base(floating_base);
    for (const auto& joint : joints) {
      description.joint_names().push_back(joint);
    }
    for (int i = 0; i < force_torque_sensors; ++i) {
      wbi::msg::SensorInfo sensor;
      sensor.name("ft_" + std::to_string(i));
      sensor.kind(wbi::msg::SensorKind::FORCE_TORQUE);
      if (static_cast<std::size_t>(i) < force_torque_frames.size()) {
        sensor.frame(force_torque_frames[static_cast<std::size_t>(i)]);
      }
      description.sensors().push_back(sensor);
    }
    for (const auto& joint : torque_sensors) {
      wbi::msg::SensorInfo sensor;
      sensor.name(joint);
      sensor.kind(wbi::msg::SensorKind::JOINT_TORQUE);
      description.sensors().push_back(sensor);
    }
    if (imu) {
      wbi::msg::SensorInfo sensor;
      sensor.name("imu");
      sensor.kind(wbi::msg::SensorKind::IMU);
      description.sensors().push_back(sensor);
    }
    wrenches_.resize(static_cast<std::size_t>(force_torque_sensors));
    description_.publish(description);
    wbi::runtime::Registry registry;
    wbi::estimator::register_components(registry);
    runner_ = std::make_unique<wbi::runtime::ComponentRunner>(
        registry.create("estimator"),
        wbi::runtime::ComponentContext{"estimator", "estimator", &participant_, &clock_});
    runner_->configure(wbi::runtime::Parameters::from_string(parameters_yaml, "estimator"));
    runner_->activate();
    EXPECT_TRUE(sensors_.wait_for_subscribers(1, 10s));
    EXPECT_TRUE(state_.wait_for_publishers(1, 10s));
  }

  // Publishes one sample (sequence k, stamp k ms unless given) and returns the
  // estimate made from it.
  wbi::msg::StateEstimate step(std::uint64_t k, const Eigen::VectorXd& q,
                               std::int64_t stamp_ns = -1) {
    wbi::msg::SensorSample sample;
    sample.header().robot(robot_);
    sample.header().seq(k);
    sample.header().stamp_ns(stamp_ns >= 0 ? stamp_ns : static_cast<std::int64_t>(k) * 1'000'000);
    sample.encoder_position().assign(q.data(), q.data() + q.size());
    sample.force_torque() = wrenches_;
    sample.joint_torque() = torques_;
    sample.imus() = imus_;
    // Best-effort stream: send again until this sample's estimate comes back.
    for (int attempt = 0; attempt < 50; ++attempt) {
      sensors_.publish(sample);
      if (state_.wait_newer(received_, received_.count, 100ms) &&
          received_.sample.header().seq() == k) {
        return received_.sample;
      }
    }
    ADD_FAILURE() << "no estimate for sample " << k;
    return {};
  }

  // The F/T reading of sensor i in the next samples: force (f, 2f, 3f), torque (−f, −2f, −3f).
  void set_wrench(std::size_t i, double f) {
    auto& w = wrenches_.at(i).wrench();
    w.force().x(f);
    w.force().y(2 * f);
    w.force().z(3 * f);
    w.torque().x(-f);
    w.torque().y(-2 * f);
    w.torque().z(-3 * f);
  }

  // The F/T readings of the next samples, (force, torque) per sensor; fewer
  // than the description has makes samples that lack some.
  void set_readings(const std::vector<wbi::model::Vector6d>& readings) {
    wrenches_.resize(readings.size());
    for (std::size_t i = 0; i < readings.size(); ++i) {
      auto& w = wrenches_[i].wrench();
      const auto& r = readings[i];
      w.force().x(r[0]);
      w.force().y(r[1]);
      w.force().z(r[2]);
      w.torque().x(r[3]);
      w.torque().y(r[4]);
      w.torque().z(r[5]);
    }
  }

  // The joint torques of the next samples (robot order; empty: none).
  void set_torques(std::vector<double> torques) { torques_ = std::move(torques); }

  // The IMU reading of the next samples: orientation in the world, accelerometer
  // (proper acceleration, IMU axes); the gyroscope reads 0.
  void set_imu(const Eigen::Quaterniond& orientation, const Eigen::Vector3d& accelerometer) {
    wbi::msg::ImuReading reading;
    reading.orientation().w(orientation.w());
    reading.orientation().x(orientation.x());
    reading.orientation().y(orientation.y());
    reading.orientation().z(orientation.z());
    reading.linear_acceleration().x(accelerometer.x());
    reading.linear_acceleration().y(accelerometer.y());
    reading.linear_acceleration().z(accelerometer.z());
    imus_ = {reading};
  }

  wbi::dds::Publisher<wbi::msg::EstimatorParameter>& parameters() { return parameters_; }
  wbi::dds::Participant& participant() { return participant_; }

  // Publishes one sample without waiting for its estimate.
  void send(std::uint64_t k, const Eigen::VectorXd& q) {
    wbi::msg::SensorSample sample;
    sample.header().robot(robot_);
    sample.header().seq(k);
    sample.header().stamp_ns(static_cast<std::int64_t>(k) * 1'000'000);
    sample.encoder_position().assign(q.data(), q.data() + q.size());
    sample.force_torque() = wrenches_;
    sensors_.publish(sample);
  }

  // The next estimate within `timeout`, if any.
  std::optional<wbi::msg::StateEstimate> next_estimate(std::chrono::milliseconds timeout) {
    if (state_.wait_newer(received_, received_.count, timeout)) {
      return received_.sample;
    }
    return std::nullopt;
  }

  // The estimator's last error as wbi/status carries it, once it contains `text`
  // (bounded wait; the last one seen otherwise).
  std::string status_error(const std::string& text) {
    wbi::dds::Received<wbi::msg::ComponentStatus> got;
    std::string error;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while (error.find(text) == std::string::npos && std::chrono::steady_clock::now() < deadline) {
      runner_->publish_status();
      if (status_.wait_newer(got, got.count, 200ms)) {
        error = got.sample.last_error();
      }
    }
    return error;
  }

  // The estimator's status counter `name` as wbi/status carries it, once it is
  // at least `at_least` (bounded wait; the last value seen otherwise, nullopt
  // when the status never carried it).
  std::optional<std::uint64_t> status_counter(const std::string& name, std::uint64_t at_least) {
    wbi::dds::Received<wbi::msg::ComponentStatus> got;
    std::optional<std::uint64_t> value;
    const auto deadline = std::chrono::steady_clock::now() + 10s;
    while ((!value || *value < at_least) && std::chrono::steady_clock::now() < deadline) {
      runner_->publish_status();
      if (status_.wait_newer(got, got.count, 200ms)) {
        for (const auto& c : got.sample.counters()) {
          if (c.name().to_string() == name) {
            value = c.value();
          }
        }
      }
    }
    return value;
  }

 private:
  std::string robot_;
  wbi::dds::Participant participant_{"estimator_test"};
  wbi::runtime::SystemClock clock_;
  wbi::dds::Publisher<wbi::msg::RobotDescription> description_;
  wbi::dds::Publisher<wbi::msg::SensorSample> sensors_;
  wbi::dds::Publisher<wbi::msg::EstimatorParameter> parameters_;
  wbi::dds::Subscriber<wbi::msg::StateEstimate> state_;
  wbi::dds::Subscriber<wbi::msg::ComponentStatus> status_{participant_, topics::kStatus,
                                                          qos::kStatus};
  wbi::dds::Received<wbi::msg::StateEstimate> received_;
  std::vector<wbi::msg::ForceTorqueReading> wrenches_;
  std::vector<double> torques_;
  std::vector<wbi::msg::ImuReading> imus_;
  std::unique_ptr<wbi::runtime::ComponentRunner> runner_;
};

TEST(EstimatorComponent, ForceTorqueEstimatesAreTheReadingsLowPassed) {
  EstimatorFixture fixture("ft", {"a"}, "robot: ft\ntorque_cutoff_hz: 5\n", 2);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(1);
  fixture.set_wrench(0, 10.0);
  fixture.set_wrench(1, -4.0);
  auto state = fixture.step(0, q);
  ASSERT_EQ(state.force_torque().size(), 2u);  // the first sample sets the filter
  EXPECT_DOUBLE_EQ(state.force_torque()[0].force().y(), 20.0);
  EXPECT_DOUBLE_EQ(state.force_torque()[1].torque().z(), 12.0);
  fixture.set_wrench(0, 20.0);  // a step: the estimate follows at 5 Hz
  state = fixture.step(1, q);
  const double first = state.force_torque()[0].force().x();
  EXPECT_GT(first, 10.0);
  EXPECT_LT(first, 11.0);
  for (std::uint64_t k = 2; k <= 1000; ++k) {
    state = fixture.step(k, q);
  }
  EXPECT_NEAR(state.force_torque()[0].force().z(), 60.0, 1e-6);
  EXPECT_NEAR(state.force_torque()[0].torque().x(), -20.0, 1e-6);
  EXPECT_NEAR(state.force_torque()[1].force().x(), -4.0, 1e-6);
}

// joint_torques: force_torque — the humanoid at rest with known wrenches on
// its soles and chest: the state carries the model's joint torques and those
// wrenches, computed from the two foot F/T readings; a NaN reading is flagged
// and counted, and samples without every reading are named.
TEST(EstimatorComponent, JointTorquesFromForceTorqueSensors) {
  const auto urdf = wbi::test::project_model("humanoid.urdf");
  const wbi::model::Model m = wbi::model::load_urdf_file(urdf.string());
  std::mt19937 rng(4);
  const auto s = wbi::test::static_state(m, {"l_sole", "r_sole"}, "chest", rng);
  wbi::test::SensorReference reference(
      urdf, {{"l_foot_ft", "l_foot_ft_sensor"}, {"r_foot_ft", "r_foot_ft_sensor"}});
  const auto readings = reference.readings(m, s);
  const Eigen::Vector3d p = s.q.head<3>();
  const auto& o = s.q.segment<4>(3);
  std::ostringstream yaml;
  yaml.precision(17);
  yaml << "robot: ftt\nurdf: " << urdf.string() << "\nbase: fixed\nbase_position: [" << p[0] << ", "
       << p[1] << ", " << p[2] << "]\nbase_quaternion: [" << o[0] << ", " << o[1] << ", " << o[2]
       << ", " << o[3]
       << "]\njoint_torques: force_torque\ncontact_links: [l_sole, r_sole]\n"
          "extra_links: [chest]\n";
  EstimatorFixture fixture("ftt", m.joint_name, yaml.str(), 2, {}, {"l_foot", "r_foot"},
                           /*floating_base=*/true);
  fixture.set_readings(readings);
  const Eigen::VectorXd q = s.q.tail(m.n_joints);
  wbi::msg::StateEstimate state;
  for (std::uint64_t k = 0; k < 3; ++k) {
    state = fixture.step(k, q);
  }
  ASSERT_EQ(state.tau().size(), static_cast<std::size_t>(m.n_joints));
  for (int j = 0; j < m.n_joints; ++j) {
    EXPECT_NEAR(state.tau()[static_cast<std::size_t>(j)], s.tau[j], 1e-6) << m.joint_name[j];
  }
  ASSERT_EQ(state.external_wrenches().size(), 3u);
  const char* links[] = {"l_sole", "r_sole", "chest"};
  for (std::size_t h = 0; h < 3; ++h) {
    const auto& e = state.external_wrenches()[h];
    EXPECT_EQ(e.link().to_string(), links[h]);
    EXPECT_EQ(e.contact(), h < 2);
    EXPECT_TRUE(e.valid());
    EXPECT_NEAR(e.wrench().force().z(), s.wrenches[h].wrench[2], 1e-6) << links[h];
    EXPECT_NEAR(e.wrench().torque().x(), s.wrenches[h].wrench[3], 1e-6) << links[h];
  }
  auto bad = readings;
  bad[1][2] = std::nan("");
  fixture.set_readings(bad);
  state = fixture.step(3, q);
  EXPECT_FALSE(state.external_wrenches()[1].valid());
  EXPECT_TRUE(state.external_wrenches()[0].valid());
  for (const double tau : state.tau()) {
    ASSERT_TRUE(std::isfinite(tau));
  }
  EXPECT_GE(fixture.status_counter("invalid_torque_estimates", 1).value_or(0), 1u);
  fixture.set_readings({readings[0]});
  fixture.send(4, q);
  EXPECT_NE(fixture.status_error("missing: ft_1").find("sensor samples carry 1 F/T readings"),
            std::string::npos);
}

// torque_accelerations: imu — the humanoid, at rest in velocity but with its base
// accelerating (pushed), held by its soles and chest: the base's acceleration from
// the IMU (its orientation turns the accelerometer into the world, gravity added
// back) puts the push's inertia into the balance, and the wrenches and torques are
// recovered; the quasi-static estimate (none) misses the chest's by m a.
TEST(EstimatorComponent, JointTorquesWithTheBaseAccelerationOfTheImu) {
  const auto urdf = wbi::test::project_model("humanoid.urdf");
  const wbi::model::Model m = wbi::model::load_urdf_file(urdf.string());
  std::mt19937 rng(7);
  const Eigen::Vector3d acceleration(0.8, -0.5, 0.3);  // of the base, world [m/s²]
  const auto s = wbi::test::static_state(m, {"l_sole", "r_sole"}, "chest", rng, acceleration);
  wbi::test::SensorReference reference(
      urdf, {{"l_foot_ft", "l_foot_ft_sensor"}, {"r_foot_ft", "r_foot_ft_sensor"}});
  const auto readings = reference.readings(m, s);
  const Eigen::Quaterniond imu_orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Vector3d gravity(0, 0, -9.81);
  const Eigen::Vector3d accelerometer = imu_orientation.inverse() * (acceleration - gravity);
  const Eigen::Vector3d p = s.q.head<3>();
  const auto& o = s.q.segment<4>(3);
  const auto chest_force = [&](const std::string& robot, const std::string& accelerations) {
    std::ostringstream yaml;
    yaml.precision(17);
    yaml << "robot: " << robot << "\nurdf: " << urdf.string() << "\nbase: fixed\nbase_position: ["
         << p[0] << ", " << p[1] << ", " << p[2] << "]\nbase_quaternion: [" << o[0] << ", " << o[1]
         << ", " << o[2] << ", " << o[3]
         << "]\njoint_torques: force_torque\ncontact_links: [l_sole, r_sole]\n"
            "extra_links: [chest]\ntorque_accelerations: "
         << accelerations << "\n";
    EstimatorFixture fixture(robot, m.joint_name, yaml.str(), 2, {}, {"l_foot", "r_foot"},
                             /*floating_base=*/true, /*imu=*/true);
    fixture.set_readings(readings);
    fixture.set_imu(imu_orientation, accelerometer);
    const Eigen::VectorXd q = s.q.tail(m.n_joints);
    wbi::msg::StateEstimate state;
    for (std::uint64_t k = 0; k < 3; ++k) {
      state = fixture.step(k, q);
    }
    if (accelerations == "imu") {
      for (int j = 0; j < m.n_joints; ++j) {
        EXPECT_NEAR(state.tau()[static_cast<std::size_t>(j)], s.tau[j], 1e-6) << m.joint_name[j];
      }
    }
    const auto& f = state.external_wrenches().at(2).wrench().force();
    return Eigen::Vector3d(f.x(), f.y(), f.z());
  };
  const Eigen::Vector3d true_chest = s.wrenches[2].wrench.head<3>();
  EXPECT_LT((chest_force("ftt_imu", "imu") - true_chest).norm(), 1e-6);
  // Quasi-static, the chest takes the whole robot's m a (the humanoid: ~34 kg).
  EXPECT_GT((chest_force("ftt_none", "none") - true_chest).norm(), 10.0);
}

// Joint torques: a joint without a sensor (NaN on the wire, idl/sensors.idl)
// and a sample without any leave 0 in the state, never NaN.
TEST(EstimatorComponent, JointsWithoutATorqueSensorEstimateZeroNotNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EstimatorFixture some("tau_some", {"a", "b", "c"}, "robot: tau_some\n", 0, {"b"});
  some.set_torques({nan, 2.5, nan});
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(3);
  for (std::uint64_t k = 0; k < 3; ++k) {
    const auto state = some.step(k, q);
    ASSERT_EQ(state.tau().size(), 3u);
    EXPECT_EQ(state.tau()[0], 0.0);
    EXPECT_EQ(state.tau()[1], 2.5);  // unfiltered (torque_cutoff_hz: 0)
    EXPECT_EQ(state.tau()[2], 0.0);
  }
  EstimatorFixture none("tau_none", {"a", "b"}, "robot: tau_none\n");
  none.set_torques({});
  const auto state = none.step(0, Eigen::VectorXd::Zero(2));
  ASSERT_EQ(state.tau().size(), 2u);
  EXPECT_EQ(state.tau()[0], 0.0);
  EXPECT_EQ(state.tau()[1], 0.0);
}

TEST(EstimatorComponent, EstimatesFollowEverySampleWithItsStamp) {
  EstimatorFixture fixture("ramp", {"a", "b"}, "robot: ramp\nmethod: kalman\n");
  const Eigen::Vector2d rate(0.5, -1.0);  // rad/s
  wbi::msg::StateEstimate state;
  for (std::uint64_t k = 0; k < 300; ++k) {
    const Eigen::Vector2d q = Eigen::Vector2d(0.1, 0.2) + rate * (1e-3 * static_cast<double>(k));
    state = fixture.step(k, q);
    ASSERT_EQ(state.header().stamp_ns(), static_cast<std::int64_t>(k) * 1'000'000);
    ASSERT_DOUBLE_EQ(state.q()[1], q[1]);
  }
  EXPECT_NEAR(state.dq()[0], 0.5, 1e-3);
  EXPECT_NEAR(state.dq()[1], -1.0, 1e-3);
  EXPECT_NEAR(state.ddq()[0], 0.0, 1e-2);
  EXPECT_DOUBLE_EQ(state.base_pose().orientation().w(), 1.0);  // base: fixed, identity
  EXPECT_EQ(state.warnings(), 0u);
}

TEST(EstimatorComponent, StampWarningsAreCountersOnTheStatusTopic) {
  EstimatorFixture fixture("stamps", {"a"}, "robot: stamps\nmethod: backward-difference\n");
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 0.1);
  for (std::uint64_t k = 0; k < 10; ++k) {
    fixture.step(k, q);
  }
  fixture.step(10, q, 9'000'000);   // the stamp of sample 9 again
  fixture.step(11, q, 5'000'000);   // older than the last one
  fixture.step(12, q, 30'000'000);  // 18 samples missing
  EXPECT_GE(fixture.status_counter("duplicate_stamps", 1).value_or(0), 1u);
  EXPECT_GE(fixture.status_counter("out_of_order_stamps", 1).value_or(0), 1u);
  EXPECT_GE(fixture.status_counter("dropped_samples", 1).value_or(0), 1u);
  EXPECT_EQ(fixture.status_counter("non_finite_samples", 0), std::optional<std::uint64_t>(0));
}

Eigen::Matrix4d pose_of(const wbi::msg::Pose& p) {
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H.topLeftCorner<3, 3>() = Eigen::Quaterniond(p.orientation().w(), p.orientation().x(),
                                               p.orientation().y(), p.orientation().z())
                                .toRotationMatrix();
  H.topRightCorner<3, 1>() << p.position().x(), p.position().y(), p.position().z();
  return H;
}

TEST(EstimatorComponent, FixedLinkBaseKeepsTheStanceFootStill) {
  const auto urdf = wbi::test::project_model("humanoid.urdf").string();
  const auto model = wbi::model::load_urdf_file(urdf);
  std::vector<std::string> joints(model.joint_name.begin(), model.joint_name.end());
  EstimatorFixture fixture("walker", joints,
                           "robot: walker\nbase: fixed_link\nurdf: " + urdf +
                               "\nfixed_link: l_sole\nbase_position: [0, 0, 0.555]\n");
  wbi::model::Data data(model);
  const auto sole_in_world = [&](const wbi::msg::StateEstimate& s, const char* frame) {
    Eigen::VectorXd q(model.nq);
    const Eigen::Matrix4d H = pose_of(s.base_pose());
    const Eigen::Quaterniond o(Eigen::Matrix3d(H.topLeftCorner<3, 3>()));
    q << H.topRightCorner<3, 1>(), o.w(), o.x(), o.y(), o.z(),
        Eigen::Map<const Eigen::VectorXd>(s.q().data(), model.n_joints);
    wbi::model::forward_kinematics(model, data, q);
    return Eigen::Matrix4d(wbi::model::frame_pose(model, data, model.frame_id(frame)));
  };

  // Bend the left knee and hip over 0.2 s: the base moves, l_sole does not.
  const int knee = model.joint_id("l_knee");
  const int hip = model.joint_id("l_hip_pitch");
  Eigen::VectorXd q = Eigen::VectorXd::Zero(model.n_joints);
  const auto first = fixture.step(0, q);
  const Eigen::Matrix4d sole_start = sole_in_world(first, "l_sole");
  EXPECT_NEAR(sole_start(2, 3), 0.0, 1e-6);  // the base started at 0.555 m: the sole on the ground
  wbi::msg::StateEstimate state;
  for (std::uint64_t k = 1; k <= 200; ++k) {
    q[knee] = 0.4 * static_cast<double>(k) / 200.0;
    q[hip] = -0.2 * static_cast<double>(k) / 200.0;
    state = fixture.step(k, q);
  }
  EXPECT_TRUE(sole_in_world(state, "l_sole").isApprox(sole_start, 1e-9));
  EXPECT_LT(pose_of(state.base_pose())(2, 3), 0.555 - 0.01);  // the pelvis went down
  // The base velocity makes the sole's velocity zero: J_sole ν = 0.
  Eigen::VectorXd nu(model.nv);
  nu << Eigen::Map<const Eigen::Matrix<double, 6, 1>>(state.base_velocity().data()),
      Eigen::Map<const Eigen::VectorXd>(state.dq().data(), model.n_joints);
  const Eigen::Matrix4d H = pose_of(state.base_pose());
  Eigen::VectorXd q_full(model.nq);
  const Eigen::Quaterniond o(Eigen::Matrix3d(H.topLeftCorner<3, 3>()));
  q_full << H.topRightCorner<3, 1>(), o.w(), o.x(), o.y(), o.z(), q;
  wbi::model::forward_kinematics(model, data, q_full);
  const Eigen::VectorXd sole_velocity =
      wbi::model::frame_jacobian(model, data, model.frame_id("l_sole")) * nu;
  EXPECT_LT(sole_velocity.norm(), 1e-9);
  EXPECT_GT(nu.head<3>().norm(), 0.05);  // the base does move

  // Switch the stance foot: from now on r_sole stays where it is.
  wbi::msg::EstimatorParameter switch_foot;
  switch_foot.name("fixed_link");
  switch_foot.text("r_sole");
  ASSERT_TRUE(fixture.parameters().wait_for_subscribers(1, 10s));
  fixture.parameters().publish(switch_foot);
  ASSERT_TRUE(fixture.parameters().wait_acknowledged(5s));
  const Eigen::Matrix4d right_before = sole_in_world(fixture.step(201, q), "r_sole");
  q[knee] = 0.0;
  const auto after = fixture.step(202, q);
  EXPECT_TRUE(sole_in_world(after, "r_sole").isApprox(right_before, 1e-9));
}

// base: topic publishes no estimate before the first base sample (an identity base
// would throw a balancing controller off): the sensor sample waits, and is estimated
// with the base of the first base sample.
TEST(EstimatorComponent, TopicBaseWaitsForTheFirstBaseSample) {
  EstimatorFixture fixture("truth", {"a"}, "robot: truth\nbase: topic\n");
  wbi::dds::Publisher<wbi::msg::GroundTruth> truth(fixture.participant(),
                                                   topics::ground_truth("truth"), qos::kStream);
  ASSERT_TRUE(truth.wait_for_subscribers(1, 10s));
  fixture.send(0, Eigen::VectorXd::Constant(1, 0.1));
  // Absence can only be observed for a while: half a second without an estimate.
  EXPECT_FALSE(fixture.next_estimate(500ms).has_value()) << "an estimate without a base sample";

  wbi::msg::GroundTruth base;
  base.header().robot("truth");
  base.base_pose().position().x(1.0);
  base.base_pose().position().y(2.0);
  base.base_pose().position().z(3.0);
  base.base_pose().orientation().w(1.0);
  base.base_velocity()[1] = 0.5;
  std::optional<wbi::msg::StateEstimate> state;
  for (int attempt = 0; attempt < 50 && !state; ++attempt) {  // best effort: send again
    truth.publish(base);
    state = fixture.next_estimate(100ms);
  }
  ASSERT_TRUE(state.has_value()) << "the waiting sample was never estimated";
  EXPECT_EQ(state->header().seq(), 0u);  // the sample sent before the base sample
  EXPECT_DOUBLE_EQ(state->base_pose().position().x(), 1.0);
  EXPECT_DOUBLE_EQ(state->base_pose().position().z(), 3.0);
  EXPECT_DOUBLE_EQ(state->base_velocity()[1], 0.5);
  // From now on every sample is estimated once the ground truth of its tick is there.
  base.header().seq(1);
  truth.publish(base);
  const auto next = fixture.step(1, Eigen::VectorXd::Constant(1, 0.2));
  EXPECT_DOUBLE_EQ(next.base_pose().position().y(), 2.0);
}

// A tick's inputs (components/estimator/README.md): the sample of tick k takes
// the ground truth of tick k, whichever comes first, never the tick before's:
// a sample that comes first waits for it.
TEST(EstimatorComponent, TopicBaseTakesTheGroundTruthOfItsTick) {
  EstimatorFixture fixture("truth_tick", {"a"}, "robot: truth_tick\nbase: topic\n");
  wbi::dds::Publisher<wbi::msg::GroundTruth> truth(
      fixture.participant(), topics::ground_truth("truth_tick"), qos::kStream);
  ASSERT_TRUE(truth.wait_for_subscribers(1, 10s));
  wbi::msg::GroundTruth base;
  base.header().robot("truth_tick");
  base.base_pose().orientation().w(1.0);
  for (std::uint64_t k = 0; k < 4; ++k) {
    base.header().seq(k);
    base.base_pose().position().x(static_cast<double>(k));
    if (k % 2 == 0) {  // the ground truth first
      truth.publish(base);
      fixture.send(k, Eigen::VectorXd::Constant(1, 0.1));
    } else {  // the sample first: it waits
      fixture.send(k, Eigen::VectorXd::Constant(1, 0.1));
      EXPECT_FALSE(fixture.next_estimate(300ms).has_value()) << "tick " << k << " did not wait";
      truth.publish(base);
    }
    const auto state = fixture.next_estimate(5s);
    ASSERT_TRUE(state.has_value()) << "no estimate of tick " << k;
    EXPECT_EQ(state->header().seq(), k);
    EXPECT_EQ(state->base_pose().position().x(), static_cast<double>(k));
  }
  EXPECT_EQ(fixture.status_counter("samples_with_late_inputs", 0).value_or(99), 0u);
}

// accelerations: model in lockstep (lockstep_controllers): the sample of tick k
// waits for the named controller's command answering tick k − 1, the one the
// robot applied before stepping to k; a mode switch (kNoTick) answers no tick.
// A command that does not come within lockstep_timeout_s: the sample is
// estimated without it, counted, and the controller is not waited for again
// until it answers.
TEST(EstimatorComponent, LockstepSampleWaitsForTheCommandsOfTheTickBefore) {
  const auto urdf = wbi::test::project_model("arm7.urdf");
  wbi::model::LoadOptions load;
  load.fixed_base = true;
  const wbi::model::Model m = wbi::model::load_urdf_file(urdf.string(), load);
  EstimatorFixture fixture("lockstep_mk", m.joint_name,
                           "robot: lockstep_mk\nurdf: " + urdf.string() +
                               "\naccelerations: model\nlockstep_controllers: [pd]\n"
                               "lockstep_timeout_s: 1.0\n");
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(
      fixture.participant(), topics::commands("lockstep_mk"), qos::kCommand);
  ASSERT_TRUE(commands.wait_for_subscribers(1, 10s));  // the estimator's commands reader
  wbi::msg::ActuatorCommand command;
  command.header().robot("lockstep_mk");
  command.controller("pd");
  for (int j = 0; j < m.n_joints; ++j) {
    command.joints().push_back(static_cast<unsigned short>(j));
    command.modes().push_back(wbi::msg::ControlMode::TORQUE);
  }
  command.references().assign(static_cast<std::size_t>(m.n_joints), 0.0);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(m.n_joints, 0.2);
  fixture.send(0, q);  // tick 0 answers nothing before it
  ASSERT_TRUE(fixture.next_estimate(5s).has_value());
  command.tick(wbi::msg::kNoTick);  // the controller's mode switch
  commands.publish(command);
  fixture.send(1, q);
  EXPECT_FALSE(fixture.next_estimate(300ms).has_value()) << "tick 1 did not wait for tick 0's";
  command.tick(0);
  commands.publish(command);
  auto state = fixture.next_estimate(5s);
  ASSERT_TRUE(state.has_value());
  EXPECT_EQ(state->header().seq(), 1u);
  EXPECT_EQ(fixture.status_counter("samples_with_late_inputs", 0).value_or(99), 0u);
  // The controller stops answering: tick 2 is estimated after lockstep_timeout_s, counted.
  const auto sent = std::chrono::steady_clock::now();
  fixture.send(2, q);
  state = fixture.next_estimate(5s);
  ASSERT_TRUE(state.has_value());
  EXPECT_EQ(state->header().seq(), 2u);
  EXPECT_GE(std::chrono::steady_clock::now() - sent, 900ms);
  EXPECT_EQ(fixture.status_counter("samples_with_late_inputs", 1).value_or(0), 1u);
  // Not waited for again until it answers.
  fixture.send(3, q);
  state = fixture.next_estimate(300ms);
  ASSERT_TRUE(state.has_value()) << "tick 3 waited for a controller that stopped";
  EXPECT_EQ(state->header().seq(), 3u);
}

// base: legged on a robot whose description has no IMU: named on the status topic,
// and no estimate with a made-up base.
TEST(EstimatorComponent, LeggedBaseWithoutAnImuIsReported) {
  const auto urdf = wbi::test::project_model("humanoid.urdf").string();
  const auto model = wbi::model::load_urdf_file(urdf);
  std::vector<std::string> joints(model.joint_name.begin(), model.joint_name.end());
  EstimatorFixture fixture("blind", joints, "robot: blind\nbase: legged\nurdf: " + urdf + "\n");
  fixture.send(0, Eigen::VectorXd::Zero(model.n_joints));
  EXPECT_NE(fixture.status_error("has no IMU").find("robot 'blind' has no IMU"), std::string::npos);
  EXPECT_FALSE(fixture.next_estimate(100ms).has_value());
  // The same for the torques' accelerations.
  EstimatorFixture torques("blind_torques", joints,
                           "robot: blind_torques\nurdf: " + urdf +
                               "\njoint_torques: force_torque\ncontact_links: [l_sole, r_sole]\n"
                               "extra_links: [chest]\ntorque_accelerations: imu\n",
                           2, {}, {"l_foot", "r_foot"}, /*floating_base=*/true);
  torques.send(0, Eigen::VectorXd::Zero(model.n_joints));
  EXPECT_NE(torques.status_error("no IMU").find("torque_accelerations: imu: the robot has no IMU"),
            std::string::npos)
      << torques.status_error("no IMU");
  EXPECT_FALSE(torques.next_estimate(100ms).has_value());
}

// accelerations: model on the project's arm, driven in torque control by the
// test: each tick the test sends the torques (gravity, damping and a sine per
// joint, ~18 rad/s² RMS) on the commands topic, integrates the arm's dynamics over the tick
// and sends the quantised encoder positions. The estimator's accelerations
// come from those torques through the model, corrected by the encoders: their
// error is at most half the adaptive window's on the same samples. Before the
// first command the joints without a torque are named.
TEST(EstimatorComponent, ModelKalmanFollowsTheCommandedTorques) {
  const auto urdf = wbi::test::project_model("arm7.urdf");
  wbi::model::LoadOptions load;
  load.fixed_base = true;
  const wbi::model::Model m = wbi::model::load_urdf_file(urdf.string(), load);
  wbi::model::Data data(m);
  const int n = m.n_joints;
  EstimatorFixture fixture("mk", m.joint_name,
                           "robot: mk\nurdf: " + urdf.string() + "\naccelerations: model\n");
  wbi::dds::Publisher<wbi::msg::ActuatorCommand> commands(fixture.participant(),
                                                          topics::commands("mk"), qos::kCommand);
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  const double step = 2.0 * std::numbers::pi / 16384.0;  // 14-bit encoders
  Eigen::VectorXd q = Eigen::VectorXd::Constant(n, 0.2);
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd quantised(n);
  const auto encoders = [&] {
    for (int j = 0; j < n; ++j) {
      quantised[j] = step * std::round(q[j] / step);
    }
    return quantised;
  };
  // No command yet: the model cannot predict, the estimator says which joints lack a torque.
  fixture.step(0, encoders());
  EXPECT_NE(fixture.status_error("no torque command for").find(m.joint_name[0]), std::string::npos);

  // Damping and sine amplitude scaled by each joint's inertia (0.0006-3.5 kg m²):
  // ~20 rad/s² on every joint, and stable at the integration's 0.1 ms.
  const Eigen::VectorXd inertia = wbi::model::mass_matrix(m, data, q).diagonal();
  const auto window = wbi::estimation::make_estimator("adaptive-window", n);
  wbi::msg::ActuatorCommand command;
  command.header().robot("mk");
  command.controller("test");
  for (int j = 0; j < n; ++j) {
    command.joints().push_back(static_cast<unsigned short>(j));
    command.modes().push_back(wbi::msg::ControlMode::TORQUE);
  }
  command.references().assign(static_cast<std::size_t>(n), 0.0);
  double sum_model = 0.0;
  double sum_window = 0.0;
  double sum_truth = 0.0;
  for (std::uint64_t k = 1; k <= 1500; ++k) {
    const double t = 1e-3 * static_cast<double>(k);
    // The torques of this tick, from the state at its start; the true
    // acceleration at the sample is the forward dynamics of them.
    Eigen::VectorXd tau =
        wbi::model::gravity_forces(m, data, q, gravity) - 20.0 * inertia.cwiseProduct(dq);
    for (int j = 0; j < n; ++j) {
      tau[j] += 20.0 * inertia[j] * std::sin(2.0 * std::numbers::pi * (1.0 + 0.7 * j) * t);
    }
    const Eigen::VectorXd ddq_true = wbi::model::forward_dynamics(m, data, q, dq, tau, gravity);
    std::copy(tau.data(), tau.data() + n, command.references().begin());
    commands.publish(command);  // reliable: before the sample, in order from this participant
    const auto state = fixture.step(k, encoders());
    window->update(static_cast<std::int64_t>(k) * 1'000'000, quantised);
    if (k > 300) {  // after the filters' start
      for (int j = 0; j < n; ++j) {
        const double e = state.ddq()[static_cast<std::size_t>(j)] - ddq_true[j];
        const double w = window->acceleration()[j] - ddq_true[j];
        sum_model += e * e;
        sum_window += w * w;
        sum_truth += ddq_true[j] * ddq_true[j];
      }
    }
    for (int sub = 0; sub < 10; ++sub) {  // the tick, semi-implicit Euler at 0.1 ms
      dq += 1e-4 * wbi::model::forward_dynamics(m, data, q, dq, tau, gravity);
      q += 1e-4 * dq;
    }
  }
  const double count = 1200.0 * n;
  const double rms_model = std::sqrt(sum_model / count);
  const double rms_window = std::sqrt(sum_window / count);
  const double rms_truth = std::sqrt(sum_truth / count);
  std::printf(
      "accelerations: model %.3f rad/s², adaptive window %.3f rad/s², signal %.3f rad/s² RMS\n",
      rms_model, rms_window, rms_truth);
  EXPECT_LE(rms_model, 0.5 * rms_window)
      << "accelerations: model " << rms_model << " rad/s², adaptive window " << rms_window
      << " rad/s², signal " << rms_truth << " rad/s²";
  EXPECT_GT(rms_truth, 5.0 * rms_model) << "the motion is too slow to tell";
  EXPECT_GE(fixture.status_counter("samples_without_model_acceleration", 1).value_or(0), 1u);
}

// A floating-base robot's accelerations depend on its contact wrenches: without
// joint_torques: force_torque to estimate them, accelerations: model is refused by name.
TEST(EstimatorComponent, ModelKalmanOnAFloatingBaseNeedsTheContactWrenches) {
  const auto urdf = wbi::test::project_model("humanoid.urdf");
  const wbi::model::Model m = wbi::model::load_urdf_file(urdf.string());
  EstimatorFixture fixture("mk_float", m.joint_name,
                           "robot: mk_float\nurdf: " + urdf.string() + "\naccelerations: model\n",
                           0, {}, {}, /*floating_base=*/true);
  fixture.send(0, Eigen::VectorXd::Zero(m.n_joints));
  EXPECT_NE(fixture.status_error("accelerations: model")
                .find("accelerations: model on a floating-base robot needs joint_torques: "
                      "force_torque"),
            std::string::npos);
}

TEST(EstimatorComponent, BadParametersAreNamed) {
  wbi::dds::Participant participant("bad");
  wbi::runtime::SystemClock clock;
  wbi::runtime::Registry registry;
  wbi::estimator::register_components(registry);
  const auto configure = [&](const std::string& yaml) -> std::string {
    wbi::runtime::ComponentRunner runner(registry.create("estimator"),
                                         {"estimator", "estimator", &participant, &clock});
    try {
      runner.configure(wbi::runtime::Parameters::from_string(yaml, "component 'estimator'"));
    } catch (const std::exception& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(configure("method: kalman\n").find("robot"), std::string::npos);
  EXPECT_NE(configure("robot: r\nmethod: magic\n").find("magic"), std::string::npos);
  EXPECT_NE(configure("robot: r\nbase: fixed_link\n").find("urdf"), std::string::npos);
  EXPECT_NE(configure("robot: r\nbase: floating\n").find("base must be"), std::string::npos);
  EXPECT_NE(configure("robot: r\nbase: legged\n").find("urdf"), std::string::npos);
  EXPECT_NE(configure("robot: r\nbase: legged\nurdf: x.urdf\nfeet: [l_sole]\n").find("feet"),
            std::string::npos);
  EXPECT_NE(configure("robot: r\nbase: legged\nurdf: x.urdf\n"
                      "foot_force_torque: [l_front+, r_ft]\n")
                .find("foot_force_torque: an empty sensor name in 'l_front+'"),
            std::string::npos);
  EXPECT_NE(configure("robot: r\nvelocity_windw: 3\n").find("velocity_windw"), std::string::npos);
  EXPECT_NE(configure("robot: r\njoint_torques: guessed\n")
                .find("joint_torques must be sensors or force_torque, got 'guessed'"),
            std::string::npos);
  EXPECT_NE(configure("robot: r\njoint_torques: force_torque\n").find("needs the robot's urdf"),
            std::string::npos);
  EXPECT_NE(configure("robot: r\naccelerations: model\n")
                .find("accelerations: model needs the robot's urdf"),
            std::string::npos);
  EXPECT_NE(configure("robot: r\naccelerations: guessed\n")
                .find("accelerations must be method or model, got 'guessed'"),
            std::string::npos);
  EXPECT_NE(configure("robot: r\nurdf: x.urdf\naccelerations: model\nacceleration_model_order: 7\n")
                .find("model-kalman"),
            std::string::npos);
  EXPECT_NE(
      configure("robot: r\njoint_torques: force_torque\nurdf: x.urdf\n").find("contact_links"),
      std::string::npos);
  EXPECT_NE(configure("robot: r\njoint_torques: force_torque\nurdf: x.urdf\n"
                      "contact_links: [a]\ntorque_accelerations: measured\n")
                .find("torque_accelerations must be none, estimated or imu, got 'measured'"),
            std::string::npos);
}

}  // namespace
