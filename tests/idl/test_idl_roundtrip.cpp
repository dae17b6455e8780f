// Every wbi message type survives Fast CDR serialization unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <fastdds/rtps/common/SerializedPayload.h>
#include <wbi/dds/message_traits.hpp>

namespace {

using eprosima::fastrtps::rtps::SerializedPayload_t;

// Distinct, non-trivial values so that a swapped or dropped field shows.
struct Values {
  double next = 0.125;
  double operator()() { return next += 1.0 / 3.0; }
};

template <class T>
T round_trip(const T& sample) {
  typename wbi::dds::MessageTraits<T>::TypeSupport type;
  auto size = type.getSerializedSizeProvider(const_cast<T*>(&sample))();
  SerializedPayload_t payload(size);
  EXPECT_TRUE(type.serialize(const_cast<T*>(&sample), &payload));
  T out;
  EXPECT_TRUE(type.deserialize(&payload, &out));
  return out;
}

wbi::msg::Header header(const char* robot) {
  wbi::msg::Header h;
  h.robot(robot);
  h.stamp_ns(1'700'000'000'123'456'789LL);
  h.seq(42);
  return h;
}

std::vector<double> doubles(std::size_t n, Values& v) {
  std::vector<double> out(n);
  for (auto& x : out) {
    x = v();
  }
  return out;
}

wbi::msg::Vector3 vec3(Values& v) {
  wbi::msg::Vector3 out;
  out.x(v());
  out.y(v());
  out.z(v());
  return out;
}

wbi::msg::Pose pose(Values& v) {
  wbi::msg::Pose p;
  p.position(vec3(v));
  p.orientation().w(std::sqrt(0.5));
  p.orientation().z(std::sqrt(0.5));
  return p;
}

std::array<double, 6> six(Values& v) {
  std::array<double, 6> out{};
  for (auto& x : out) {
    x = v();
  }
  return out;
}

TEST(IdlRoundTrip, RobotDescription) {
  wbi::msg::RobotDescription d;
  d.header(header("arm"));
  d.floating_base(true);
  d.joint_names({"shoulder", "elbow"});
  wbi::msg::JointLimits limits;
  limits.position_min(-1.5);
  limits.position_max(2.5);
  limits.velocity_max(3.0);
  limits.effort_max(40.0);
  d.joint_limits({limits, limits});
  wbi::msg::SensorInfo imu;
  imu.name("imu");
  imu.kind(wbi::msg::SensorKind::IMU);
  imu.frame("head");
  d.sensors({imu});
  d.urdf_path("/tmp/arm.urdf");
  EXPECT_EQ(round_trip(d), d);
}

TEST(IdlRoundTrip, SensorSample) {
  Values v;
  wbi::msg::SensorSample s;
  s.header(header("humanoid"));
  s.encoder_position(doubles(32, v));
  s.joint_torque(doubles(32, v));
  s.motor_pwm(doubles(32, v));
  wbi::msg::ImuReading imu;
  imu.angular_velocity(vec3(v));
  imu.linear_acceleration(vec3(v));
  imu.orientation().w(1.0);
  s.imus({imu, imu});
  wbi::msg::ForceTorqueReading ft;
  ft.wrench().force(vec3(v));
  ft.wrench().torque(vec3(v));
  s.force_torque({ft, ft, ft, ft});
  const auto out = round_trip(s);
  EXPECT_EQ(out, s);
  EXPECT_EQ(out.encoder_position().size(), 32u);
}

TEST(IdlRoundTrip, GroundTruth) {
  Values v;
  wbi::msg::GroundTruth g;
  g.header(header("humanoid"));
  g.q(doubles(30, v));
  g.dq(doubles(30, v));
  g.ddq(doubles(30, v));
  g.base_pose(pose(v));
  g.base_velocity(six(v));
  g.base_acceleration(six(v));
  wbi::msg::Wrench w;
  w.force(vec3(v));
  w.torque(vec3(v));
  g.contact_wrenches({w, w});
  EXPECT_EQ(round_trip(g), g);
}

TEST(IdlRoundTrip, ActuatorCommandAndParameters) {
  Values v;
  wbi::msg::ActuatorCommand c;
  c.header(header("arm"));
  c.controller("pd_gravity");
  c.tick(1234);
  c.joints({0, 3, 6});
  c.modes({wbi::msg::ControlMode::TORQUE, wbi::msg::ControlMode::POSITION_DIRECT,
           wbi::msg::ControlMode::PWM});
  c.references(doubles(3, v));
  EXPECT_EQ(round_trip(c), c);

  wbi::msg::ControlParameters p;
  p.header(header("arm"));
  p.controller("pd_gravity");
  p.joints({1, 2});
  p.kp(doubles(2, v));
  p.ki(doubles(2, v));
  p.kd(doubles(2, v));
  p.reference_speed(doubles(2, v));
  EXPECT_EQ(round_trip(p), p);
}

TEST(IdlRoundTrip, StateEstimate) {
  Values v;
  wbi::msg::StateEstimate s;
  s.header(header("humanoid"));
  s.q(doubles(30, v));
  s.dq(doubles(30, v));
  s.ddq(doubles(30, v));
  s.tau(doubles(30, v));
  s.base_pose(pose(v));
  s.base_velocity(six(v));
  s.base_acceleration(six(v));
  s.warnings(3);
  EXPECT_EQ(round_trip(s), s);
}

TEST(IdlRoundTrip, ModelRequestAndReply) {
  Values v;
  wbi::msg::ModelRequest r;
  r.client_id("client-7");
  r.seq(99);
  r.robot("humanoid");
  r.state().base_pose(pose(v));
  r.state().base_velocity(six(v));
  r.state().q(doubles(30, v));
  r.state().dq(doubles(30, v));
  r.state().gravity().z(-9.81);
  wbi::msg::OperationRequest jacobian;
  jacobian.operation(wbi::msg::ModelOperation::JACOBIAN);
  jacobian.frame("l_sole");
  wbi::msg::OperationRequest mass;
  mass.operation(wbi::msg::ModelOperation::MASS_MATRIX);
  r.operations({mass, jacobian});
  r.nu_dot(doubles(36, v));
  r.tau(doubles(30, v));
  wbi::msg::FrameWrench fw;
  fw.frame("r_sole");
  fw.wrench().force(vec3(v));
  r.wrenches({fw});
  EXPECT_EQ(round_trip(r), r);

  wbi::msg::ModelReply reply;
  reply.client_id("client-7");
  reply.seq(99);
  reply.compute_ns(1500);
  wbi::msg::OperationResult result;
  result.operation(wbi::msg::ModelOperation::MASS_MATRIX);
  result.rows(36);
  result.cols(36);
  result.data(doubles(36 * 36, v));
  reply.results({result});
  EXPECT_EQ(round_trip(reply), reply);
  reply.error("unknown frame 'foo'");
  EXPECT_EQ(round_trip(reply).error(), "unknown frame 'foo'");
}

TEST(IdlRoundTrip, StatusAndClock) {
  wbi::msg::ComponentStatus s;
  s.header(header("arm"));
  s.instance("sensors");
  s.type("sensor");
  s.state(wbi::msg::LifecycleState::ACTIVE);
  s.rate_hz(1000.0);
  s.period_mean_s(0.001);
  s.period_jitter_s(1e-5);
  s.overruns(2);
  s.iterations(10000);
  s.last_error("none");
  wbi::msg::Counter rejected;
  rejected.name("rejected_commands");
  rejected.value(3);
  s.counters({rejected});
  EXPECT_EQ(round_trip(s), s);

  wbi::msg::SimulationClock c;
  c.time_ns(5'000'000);
  c.tick(5);
  c.step_ns(1'000'000);
  c.lockstep(true);
  EXPECT_EQ(round_trip(c), c);
}

TEST(IdlRoundTrip, Signals) {
  wbi::msg::Signals s;
  s.header(header("icub3"));
  s.source("balance");
  s.names({"com_y", "com_ref_y"});
  s.values({0.0123, -0.5});
  EXPECT_EQ(round_trip(s), s);
}

TEST(IdlRoundTrip, PlaybackCommand) {
  wbi::msg::PlaybackCommand p;
  p.header(header("arm"));
  p.action(wbi::msg::STEP);
  EXPECT_EQ(round_trip(p), p);
}

}  // namespace
