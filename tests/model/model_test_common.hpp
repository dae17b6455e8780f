// Helpers shared by the model tests: the list of models, random states,
// finite differences, relative comparisons.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "test_support.hpp"
#include "wbi/model/algorithms.hpp"

namespace wbi::test {

// The project's URDFs that exist (arm7 and humanoid are written in parallel).
inline std::vector<std::filesystem::path> project_models() {
  std::vector<std::filesystem::path> out;
  for (const char* f : {"pendulum.urdf", "double_pendulum.urdf", "arm7.urdf", "humanoid.urdf"}) {
    if (std::filesystem::exists(project_model(f))) {
      out.push_back(project_model(f));
    }
  }
  return out;
}

// Every URDF under ../shared/models (empty when absent).
inline std::vector<std::filesystem::path> shared_models() {
  std::vector<std::filesystem::path> out;
  const auto dir = shared_models_dir();
  if (!dir) {
    return out;
  }
  for (const char* f :
       {"iCubGenova09/model.urdf", "iCubGazeboV2_5/model.urdf", "talos/talos_reduced.urdf",
        "talos/talos_full_v2.urdf", "atlas/atlas.urdf", "anymal_c/anymal.urdf",
        "hyq/hyq_no_sensors.urdf", "hyq/hyq.urdf", "solo12/solo12.urdf", "panda/panda.urdf",
        "ur5/ur5_robot.urdf", "iiwa/iiwa.urdf"}) {
    out.push_back(*dir / f);
  }
  return out;
}

inline Eigen::VectorXd random_vector(int n, std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> d(-scale, scale);
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) {
    x[i] = d(rng);
  }
  return x;
}

// max |a − b| ≤ tol · max(1, max |b|)
inline ::testing::AssertionResult near_rel(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                           double tol) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure()
           << "size " << a.rows() << "x" << a.cols() << " vs " << b.rows() << "x" << b.cols();
  }
  const double scale = std::max(1.0, b.cwiseAbs().maxCoeff());
  const double err = (a - b).cwiseAbs().maxCoeff();
  if (err <= tol * scale) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "max error " << err << " > " << tol << " x " << scale;
}

// ω with exp([ω]×) = R (for small rotations).
inline Eigen::Vector3d rotation_log(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

}  // namespace wbi::test
