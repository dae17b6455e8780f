// The balancing's CoM reference: held while settling, then a sinusoid centred
// on the feet that starts where the CoM is (a controller restarted on a robot
// leaning mid-swing must not swing around the lean).
#include <algorithm>
#include <cmath>
#include <utility>

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <wbi/controllers/com_sinusoid.hpp>

namespace {

using wbi::controllers::ComSinusoid;

struct Sample {
  Eigen::Vector3d x, v, a;
};

Sample at(const ComSinusoid& reference, double t) {
  Sample s;
  reference.at(t, s.x, s.v, s.a);
  return s;
}

// Settles at `com` over the feet at `feet`, then takes the first tick after it.
ComSinusoid started(const Eigen::Vector3d& com, const Eigen::Vector3d& feet) {
  ComSinusoid reference;  // 5 cm along y, 0.2 Hz, 0.5 s settling
  reference.follow(
      0.0, [&] { return com; }, [&] { return feet; });
  reference.follow(
      0.501, [&] { return com; }, [&] { return feet; });
  return reference;
}

// Along y over the whole swing: [lowest, highest].
std::pair<double, double> swing(const ComSinusoid& reference) {
  double low = 1e9, high = -1e9;
  for (double t = 0.5; t < 5.5; t += 0.001) {
    const double y = at(reference, t).x.y();
    low = std::min(low, y);
    high = std::max(high, y);
  }
  return {low, high};
}

TEST(ComSinusoid, HoldsTheMeasuredComWhileSettling) {
  ComSinusoid reference;
  const Eigen::Vector3d com(0.01, 0.02, 0.55);
  bool feet_asked = false;
  reference.follow(
      0.2, [&] { return com; },
      [&] {
        feet_asked = true;
        return Eigen::Vector3d::Zero().eval();
      });
  const Sample s = at(reference, 0.2);
  EXPECT_TRUE(s.x.isApprox(com));
  EXPECT_TRUE(s.v.isZero());
  EXPECT_TRUE(s.a.isZero());
  EXPECT_FALSE(feet_asked) << "the feet are needed only when the sinusoid starts";
}

TEST(ComSinusoid, ARobotStandingStraightStartsAtPhaseZero) {
  const Eigen::Vector3d com(0.015, 0.0, 0.55), feet(0.0, 0.0, 0.0);
  const ComSinusoid reference = started(com, feet);
  EXPECT_NEAR(reference.phase, 0.0, 1e-12);
  EXPECT_TRUE(at(reference, 0.5).x.isApprox(com));
  const auto [low, high] = swing(reference);
  EXPECT_NEAR(low, -0.05, 1e-6);
  EXPECT_NEAR(high, 0.05, 1e-6);
}

TEST(ComSinusoid, ALeaningStartKeepsTheSwingBetweenTheFeet) {
  // Restarted at 4.5 cm out, where a ±5 cm swing around the CoM reached 9.5 cm.
  const Eigen::Vector3d com(0.015, 0.045, 0.55), feet(0.0, 0.0, 0.02);
  const ComSinusoid reference = started(com, feet);
  EXPECT_TRUE(at(reference, 0.5).x.isApprox(com)) << "no jump at the start";
  EXPECT_NEAR(reference.origin.y(), 0.0, 1e-12);
  EXPECT_NEAR(reference.origin.x(), com.x(), 1e-12) << "across the swing: the CoM's";
  EXPECT_NEAR(reference.origin.z(), com.z(), 1e-12) << "the height is the CoM's";
  const auto [low, high] = swing(reference);
  EXPECT_NEAR(low, -0.05, 1e-6);
  EXPECT_NEAR(high, 0.05, 1e-6);
}

TEST(ComSinusoid, AStartBeyondTheSwingStaysAtTheComWithTheSwingsRange) {
  const Eigen::Vector3d com(0.0, -0.08, 0.55), feet(0.0, 0.0, 0.0);
  const ComSinusoid reference = started(com, feet);
  EXPECT_TRUE(at(reference, 0.5).x.isApprox(com));
  const auto [low, high] = swing(reference);
  EXPECT_NEAR(high - low, 0.10, 1e-6);
  EXPECT_NEAR(low, -0.08, 1e-6) << "from the CoM toward the feet, not further out";
}

TEST(ComSinusoid, ANewSettlingStartsAgain) {
  // A restarted robot: the stamps' clock goes back, the reference settles again.
  ComSinusoid reference = started(Eigen::Vector3d(0.0, 0.03, 0.55), Eigen::Vector3d::Zero());
  const Eigen::Vector3d com(0.0, -0.01, 0.55), feet(0.0, 0.0, 0.0);
  reference.follow(
      0.1, [&] { return com; }, [&] { return feet; });
  EXPECT_EQ(reference.phase, 0.0);
  reference.follow(
      0.6, [&] { return com; }, [&] { return feet; });
  EXPECT_NEAR(reference.phase, std::asin(-0.01 / 0.05), 1e-12);
  EXPECT_TRUE(at(reference, 0.5).x.isApprox(com));
}

}  // namespace
