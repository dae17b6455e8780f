// <wbi/msg/eigen.hpp>: wire messages to and from Eigen. Round trips, the
// quaternion's sign and normalisation, sizes that do not match, and no heap
// allocation (built with EIGEN_RUNTIME_NO_MALLOC).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <wbi/msg/state.h>
#include <wbi/msg/eigen.hpp>

namespace {

using wbi::msg::Vector6d;
using wbi::msg::Vector7d;

// A rotation of 2 rad about a tilted axis, and a translation.
Eigen::Matrix4d some_transform() {
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H.topLeftCorner<3, 3>() = Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, -2, 3).normalized()).matrix();
  H.topRightCorner<3, 1>() << 0.5, -1.25, 2.0;
  return H;
}

wbi::msg::Pose pose(double x, double y, double z, double w, double qx, double qy, double qz) {
  wbi::msg::Pose p;
  p.position().x(x);
  p.position().y(y);
  p.position().z(z);
  p.orientation().w(w);
  p.orientation().x(qx);
  p.orientation().y(qy);
  p.orientation().z(qz);
  return p;
}

class NoMalloc {
 public:
  NoMalloc() { Eigen::internal::set_is_malloc_allowed(false); }
  ~NoMalloc() { Eigen::internal::set_is_malloc_allowed(true); }
  NoMalloc(const NoMalloc&) = delete;
  NoMalloc& operator=(const NoMalloc&) = delete;
};

TEST(EigenConversions, TransformToPoseAndBack) {
  const Eigen::Matrix4d H = some_transform();
  wbi::msg::Pose p;
  Eigen::Matrix4d back;
  {
    NoMalloc guard;
    wbi::msg::to_wire(H, p);
    wbi::msg::to_transform(p, back);
  }
  EXPECT_TRUE(back.isApprox(H, 1e-15)) << back;
  EXPECT_EQ(back.row(3), Eigen::RowVector4d(0, 0, 0, 1));
  EXPECT_EQ(p.position().y(), -1.25);
  const Eigen::Quaterniond q = wbi::msg::to_eigen(p.orientation());
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  // The quaternion is Eigen's own conversion of the rotation block, bit for bit.
  EXPECT_EQ(q.coeffs(), Eigen::Quaterniond(Eigen::Matrix3d(H.topLeftCorner<3, 3>())).coeffs());
  EXPECT_EQ(wbi::msg::orientation_of(H).coeffs(), q.coeffs());
}

TEST(EigenConversions, PoseToTransformNormalisesAndIgnoresTheSign) {
  const double h = std::sqrt(0.5);
  Eigen::Matrix4d unit;
  Eigen::Matrix4d scaled;
  Eigen::Matrix4d negated;
  wbi::msg::to_transform(pose(1, 2, 3, h, 0, 0, h), unit);  // 90° about z
  wbi::msg::to_transform(pose(1, 2, 3, 2 * h, 0, 0, 2 * h), scaled);
  wbi::msg::to_transform(pose(1, 2, 3, -h, 0, 0, -h), negated);
  Eigen::Matrix4d expected = Eigen::Matrix4d::Identity();
  expected.topLeftCorner<3, 3>() << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  expected.topRightCorner<3, 1>() << 1, 2, 3;
  EXPECT_TRUE(unit.isApprox(expected, 1e-15)) << unit;
  EXPECT_TRUE(scaled.isApprox(expected, 1e-15)) << scaled;
  EXPECT_TRUE(negated.isApprox(expected, 1e-15)) << negated;
  // A zero quaternion (a fixed base that sends zeros) is the identity rotation.
  Eigen::Matrix4d zero;
  wbi::msg::to_transform(pose(1, 2, 3, 0, 0, 0, 0), zero);
  EXPECT_TRUE((zero.topLeftCorner<3, 3>().isIdentity(0.0)));
  // The isometry is the same transform.
  EXPECT_TRUE(wbi::msg::to_isometry(pose(1, 2, 3, -2 * h, 0, 0, -2 * h))
                  .matrix()
                  .isApprox(expected, 1e-15));
}

TEST(EigenConversions, QuaternionsAndCoordinatesAreCopiedAsTheyAre) {
  // Neither normalised nor sign-changed: the consumer decides.
  const auto p = pose(0.5, -0.5, 1.5, -2.0, 0.25, 0.5, -0.75);
  const Eigen::Quaterniond q = wbi::msg::to_eigen(p.orientation());
  EXPECT_EQ(q.coeffs(), Eigen::Vector4d(0.25, 0.5, -0.75, -2.0));  // Eigen stores x, y, z, w
  Eigen::VectorXd q_model = Eigen::VectorXd::Constant(9, 7.0);
  {
    NoMalloc guard;
    wbi::msg::to_coordinates(p, q_model.head<7>());
  }
  Eigen::VectorXd expected(9);
  expected << 0.5, -0.5, 1.5, -2.0, 0.25, 0.5, -0.75, 7.0, 7.0;
  EXPECT_EQ(q_model, expected);

  wbi::msg::Quaternion wire;
  wbi::msg::to_wire(q, wire);
  EXPECT_EQ(wire, p.orientation());
  wbi::msg::Pose from_parts;
  wbi::msg::to_wire(Eigen::Vector3d(0.5, -0.5, 1.5), Eigen::Vector4d(-2.0, 0.25, 0.5, -0.75),
                    from_parts);
  EXPECT_EQ(from_parts, p);
}

TEST(EigenConversions, WrenchesAreLinearFirst) {
  Vector6d w;
  w << 1, 2, 3, 4, 5, 6;
  wbi::msg::Wrench wire;
  Eigen::VectorXd stacked = Eigen::VectorXd::Zero(12);
  {
    NoMalloc guard;
    wbi::msg::to_wire(w, wire);
    wbi::msg::to_eigen(wire, stacked.segment<6>(6));
  }
  EXPECT_EQ(wire.force().x(), 1.0);
  EXPECT_EQ(wire.force().z(), 3.0);
  EXPECT_EQ(wire.torque().x(), 4.0);
  EXPECT_EQ(wire.torque().z(), 6.0);
  EXPECT_EQ(stacked.head<6>(), Vector6d::Zero());
  EXPECT_EQ(stacked.tail<6>(), w);
}

TEST(EigenConversions, SequencesAndArrays) {
  wbi::msg::StateEstimate state;
  Eigen::VectorXd q(4);
  q << 0.1, 0.2, 0.3, 0.4;
  wbi::msg::to_wire(q, state.q());  // grows the sequence, once
  ASSERT_EQ(state.q().size(), 4u);
  const Eigen::VectorXd q2 = 2.0 * q;
  Eigen::VectorXd back = Eigen::VectorXd::Zero(4);
  Vector6d velocity;
  velocity << 1, 2, 3, 4, 5, 6;
  {
    NoMalloc guard;
    wbi::msg::to_wire(q2, state.q());  // the same size: no allocation
    wbi::msg::to_eigen(state.q(), back, "joint positions");
    wbi::msg::to_wire(velocity, state.base_velocity());
  }
  EXPECT_EQ(back, q2);
  EXPECT_EQ(state.base_velocity()[5], 6.0);
  EXPECT_EQ(wbi::msg::to_eigen(state.base_velocity()), velocity);
}

// view() reads a sequence where it is: the same memory, nothing copied.
TEST(EigenConversions, AViewOfASequenceIsItsMemory) {
  wbi::msg::StateEstimate state;
  state.q() = {0.5, -0.25, 1.0};
  const auto q = wbi::msg::view(state.q());
  ASSERT_EQ(q.size(), 3);
  EXPECT_EQ(q.data(), state.q().data());
  state.q()[1] = 7.0;
  EXPECT_EQ(q[1], 7.0);
  EXPECT_EQ(wbi::msg::view(std::vector<double>{}).size(), 0);
}

TEST(EigenConversions, SizesThatDoNotMatchNameTheField) {
  const std::vector<double> three{1.0, 2.0, 3.0};
  Eigen::VectorXd four = Eigen::VectorXd::Constant(4, 9.0);
  try {
    wbi::msg::to_eigen(three, four, "joint positions");
    FAIL() << "no error for 3 values into 4";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "joint positions: 3 values, expected 4");
  }
  EXPECT_EQ(four, Eigen::VectorXd::Constant(4, 9.0));  // untouched
}

}  // namespace
