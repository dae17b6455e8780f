// Armature (Model::joint_armature, the rotor inertia reflected through the gear
// ratio) in the loader and the algorithms:
//   loaded in ν order, kept by a reduced model, bad entries rejected naming the joint;
//   M − M(armature 0) is diag(armature) on the joint block and exactly 0 elsewhere;
//   RNEA = (M + diag) ν̇ + h and ABA inverts RNEA to 1e-9 at random states on the
//   project's arm (fixed base) and humanoid, iCub 3 and TALOS (floating base);
//   h, G, A_G and h_G do not see armature (MuJoCo's convention, model.hpp);
//   an armature of 0 for every joint gives every result of a model loaded without
//   the option bit for bit.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

#include <Eigen/Cholesky>

#include "model_test_common.hpp"

namespace wm = wbi::model;
using wbi::test::near_rel;

namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

// The models the issue names: the project's arm and humanoid, iCub 3 and TALOS.
std::vector<std::filesystem::path> armature_models() {
  std::vector<std::filesystem::path> out = {wbi::test::project_model("arm7.urdf"),
                                            wbi::test::project_model("humanoid.urdf")};
  if (const auto dir = wbi::test::shared_models_dir()) {
    out.push_back(*dir / "iCubGenova09/model.urdf");
    out.push_back(*dir / "talos/talos_reduced.urdf");
  } else {
    std::cout << wbi::test::kSharedMissing << " (expected "
              << (wbi::test::source_dir().parent_path() / "shared/models").string()
              << "): iCub 3 and TALOS not tested\n";
  }
  return out;
}

// Armature of every movable joint of `model`, between 0.01 and 0.5 (kg·m² or kg):
// the order of a real rotor reflected through a gearbox of ratio 100, and more.
std::map<std::string, double> random_armature(const wm::Model& model, std::mt19937& rng) {
  std::uniform_real_distribution<double> d(0.01, 0.5);
  std::map<std::string, double> out;
  for (const std::string& j : model.joint_name) {
    out[j] = d(rng);
  }
  return out;
}

wm::Model load(const std::filesystem::path& path, const std::map<std::string, double>& armature) {
  wm::LoadOptions options;
  options.armature = armature;
  return wm::load_urdf_file(path.string(), options);
}

// Bit-for-bit equality, so that +0 and −0 also differ.
::testing::AssertionResult same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols()) {
    return ::testing::AssertionFailure() << "sizes differ";
  }
  for (Eigen::Index c = 0; c < a.cols(); ++c) {
    for (Eigen::Index r = 0; r < a.rows(); ++r) {
      if (std::bit_cast<std::uint64_t>(a(r, c)) != std::bit_cast<std::uint64_t>(b(r, c))) {
        return ::testing::AssertionFailure()
               << "(" << r << ", " << c << "): " << a(r, c) << " vs " << b(r, c);
      }
    }
  }
  return ::testing::AssertionSuccess();
}

void expect_invalid(const std::function<void()>& f, const std::vector<std::string>& words) {
  try {
    f();
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    for (const std::string& w : words) {
      EXPECT_NE(std::string(e.what()).find(w), std::string::npos)
          << "'" << e.what() << "' does not name '" << w << "'";
    }
  }
}

}  // namespace

TEST(Armature, LoadedInJointOrderDefaultZero) {
  const auto path = wbi::test::project_model("arm7.urdf");
  const wm::Model plain = wm::load_urdf_file(path.string());
  ASSERT_EQ(plain.joint_armature.size(), static_cast<std::size_t>(plain.n_joints));
  for (double a : plain.joint_armature) {
    EXPECT_EQ(a, 0.0);
  }
  const wm::Model model = load(path, {{"joint_3", 0.25}, {"joint_1", 0.5}});
  for (int k = 0; k < model.n_joints; ++k) {
    const std::string& name = model.joint_name[static_cast<std::size_t>(k)];
    const double expected = name == "joint_1" ? 0.5 : name == "joint_3" ? 0.25 : 0.0;
    EXPECT_EQ(model.joint_armature[static_cast<std::size_t>(k)], expected) << name;
  }
}

TEST(Armature, ReducedModelKeepsTheArmatureOfKeptJoints) {
  wm::LoadOptions options;
  options.joints = {"joint_4", "joint_2"};                                    // reordered
  options.armature = {{"joint_2", 0.2}, {"joint_4", 0.4}, {"joint_5", 0.5}};  // joint_5 locked
  const wm::Model model =
      wm::load_urdf_file(wbi::test::project_model("arm7.urdf").string(), options);
  ASSERT_EQ(model.n_joints, 2);
  EXPECT_EQ(model.joint_armature, (std::vector<double>{0.4, 0.2}));
  // the reduced M sees it at the kept joints' places
  wm::LoadOptions plain = options;
  plain.armature.clear();
  const wm::Model model0 =
      wm::load_urdf_file(wbi::test::project_model("arm7.urdf").string(), plain);
  wm::Data data(model), data0(model0);
  std::mt19937 rng(4);
  const Eigen::VectorXd q = wm::random_configuration(model, rng);
  const Eigen::MatrixXd dM = wm::mass_matrix(model, data, q) - wm::mass_matrix(model0, data0, q);
  ASSERT_EQ(model.nv, 2);  // arm7's root is "world": fixed base
  EXPECT_DOUBLE_EQ(dM(0, 0), 0.4);
  EXPECT_DOUBLE_EQ(dM(1, 1), 0.2);
  EXPECT_EQ(dM(0, 1), 0.0);
}

TEST(Armature, BadEntriesNameTheJoint) {
  const std::string path = wbi::test::project_model("arm7.urdf").string();
  expect_invalid([&] { load(path, {{"elbow", 0.1}}); }, {"arm7.urdf", "unknown joint", "elbow"});
  expect_invalid(
      [&] {
        load(path, {{"base_link_fixed_joint", 0.1}});
      },
      {"base_link_fixed_joint", "fixed"});
  expect_invalid([&] { load(path, {{"joint_2", -0.5}}); }, {"joint_2", "-0.5", ">= 0"});
  expect_invalid([&] { load(path, {{"joint_3", std::nan("")}}); }, {"joint_3", "nan"});
  expect_invalid(
      [&] {
        load(path, {{"joint_4", std::numeric_limits<double>::infinity()}});
      },
      {"joint_4", "inf"});
}

TEST(Armature, MassMatrixGainsExactlyTheDiagonalOnTheJointBlock) {
  for (const auto& path : armature_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model0 = wm::load_urdf_file(path.string());
    std::mt19937 rng(5);
    const wm::Model model = load(path, random_armature(model0, rng));
    wm::Data data(model), data0(model0);
    for (int t = 0; t < 3; ++t) {
      const Eigen::VectorXd q = wm::random_configuration(model, rng);
      const Eigen::MatrixXd M = wm::mass_matrix(model, data, q);
      const Eigen::MatrixXd M0 = wm::mass_matrix(model0, data0, q);
      for (int r = 0; r < model.nv; ++r) {
        for (int c = 0; c < model.nv; ++c) {
          const int k = r - model.base_nv;
          const bool joint_diagonal = r == c && k >= 0;
          // the one addition the library makes, in the same floating-point arithmetic
          const double expected = joint_diagonal
                                      ? M0(r, c) + model.joint_armature[static_cast<std::size_t>(k)]
                                      : M0(r, c);
          ASSERT_EQ(M(r, c), expected) << "(" << r << ", " << c << ")";
        }
      }
    }
  }
}

TEST(Armature, ForwardDynamicsInvertsInverseDynamics) {
  for (const auto& path : armature_models()) {
    SCOPED_TRACE(path.string());
    std::mt19937 rng(6);
    const wm::Model model = load(path, random_armature(wm::load_urdf_file(path.string()), rng));
    // floating base, except the arm, whose root link is "world"
    EXPECT_EQ(model.floating_base, path.filename() != "arm7.urdf");
    wm::Data data(model);
    for (int t = 0; t < 5; ++t) {
      const Eigen::VectorXd q = wm::random_configuration(model, rng);
      const Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 1.5);
      const Eigen::VectorXd dnu = wbi::test::random_vector(model.nv, rng, 1.5);
      const Eigen::VectorXd tau = wm::inverse_dynamics(model, data, q, nu, dnu, kGravity);
      EXPECT_TRUE(near_rel(wm::forward_dynamics(model, data, q, nu, tau, kGravity), dnu, 1e-9));
      // RNEA = (M + diag) ν̇ + h, and ABA = (M + diag)⁻¹ (τ − h)
      const Eigen::MatrixXd M = wm::mass_matrix(model, data, q);
      const Eigen::VectorXd h = wm::bias_forces(model, data, q, nu, kGravity);
      EXPECT_TRUE(near_rel(tau, M * dnu + h, 1e-9));
      const Eigen::VectorXd tau2 = wbi::test::random_vector(model.nv, rng, 3.0);
      EXPECT_TRUE(near_rel(wm::forward_dynamics(model, data, q, nu, tau2, kGravity),
                           M.ldlt().solve(tau2 - h), 1e-7));
    }
  }
}

TEST(Armature, ForwardDynamicsOfAFixedArmWithExternalWrench) {
  const auto path = wbi::test::project_model("arm7.urdf");
  std::mt19937 rng(7);
  wm::LoadOptions options;
  options.fixed_base = true;
  options.armature = random_armature(wm::load_urdf_file(path.string()), rng);
  const wm::Model model = wm::load_urdf_file(path.string(), options);
  wm::Data data(model);
  const wm::ExternalWrench w{model.n_frames() - 1,
                             (wm::Vector6d() << 3.0, -2.0, 1.0, 0.3, 0.2, -0.1).finished()};
  for (int t = 0; t < 3; ++t) {
    const Eigen::VectorXd q = wm::random_configuration(model, rng);
    const Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 1.5);
    const Eigen::VectorXd dnu = wbi::test::random_vector(model.nv, rng, 1.5);
    const Eigen::VectorXd tau =
        wm::inverse_dynamics(model, data, q, nu, dnu, kGravity, std::span(&w, 1));
    EXPECT_TRUE(near_rel(wm::forward_dynamics(model, data, q, nu, tau, kGravity, std::span(&w, 1)),
                         dnu, 1e-9));
  }
}

TEST(Armature, NoVelocityGravityOrCentroidalTerms) {
  for (const auto& path : armature_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model0 = wm::load_urdf_file(path.string());
    std::mt19937 rng(8);
    const wm::Model model = load(path, random_armature(model0, rng));
    wm::Data data(model), data0(model0);
    const Eigen::VectorXd q = wm::random_configuration(model, rng);
    const Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 1.5);
    // ν̇ = 0 adds armature·0: equal values (a −0 may become +0)
    EXPECT_EQ(wm::bias_forces(model, data, q, nu, kGravity),
              wm::bias_forces(model0, data0, q, nu, kGravity));
    EXPECT_TRUE(same_bits(wm::gravity_forces(model, data, q, kGravity),
                          wm::gravity_forces(model0, data0, q, kGravity)));
    EXPECT_TRUE(same_bits(wm::centroidal_momentum_matrix(model, data, q),
                          wm::centroidal_momentum_matrix(model0, data0, q)));
    EXPECT_TRUE(same_bits(wm::centroidal_momentum(model, data, q, nu),
                          wm::centroidal_momentum(model0, data0, q, nu)));
  }
}

// Zero armature reproduces the model loaded without the option, bit for bit.
TEST(Armature, ZeroArmatureChangesNoBit) {
  for (const auto& path : armature_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model0 = wm::load_urdf_file(path.string());
    std::map<std::string, double> zeros;
    for (const std::string& j : model0.joint_name) {
      zeros[j] = 0.0;
    }
    const wm::Model model = load(path, zeros);
    wm::Data data(model), data0(model0);
    std::mt19937 rng(9);
    for (int t = 0; t < 3; ++t) {
      const Eigen::VectorXd q = wm::random_configuration(model, rng);
      const Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 1.5);
      const Eigen::VectorXd dnu = wbi::test::random_vector(model.nv, rng, 1.5);
      const Eigen::VectorXd tau = wbi::test::random_vector(model.nv, rng, 3.0);
      const wm::ExternalWrench w{model.n_frames() - 1,
                                 (wm::Vector6d() << 3.0, -2.0, 1.0, 0.3, 0.2, -0.1).finished()};
      EXPECT_TRUE(same_bits(wm::mass_matrix(model, data, q), wm::mass_matrix(model0, data0, q)));
      EXPECT_TRUE(same_bits(wm::bias_forces(model, data, q, nu, kGravity),
                            wm::bias_forces(model0, data0, q, nu, kGravity)));
      EXPECT_TRUE(same_bits(wm::inverse_dynamics(model, data, q, nu, dnu, kGravity),
                            wm::inverse_dynamics(model0, data0, q, nu, dnu, kGravity)));
      EXPECT_TRUE(
          same_bits(wm::inverse_dynamics(model, data, q, nu, dnu, kGravity, std::span(&w, 1)),
                    wm::inverse_dynamics(model0, data0, q, nu, dnu, kGravity, std::span(&w, 1))));
      EXPECT_TRUE(same_bits(wm::forward_dynamics(model, data, q, nu, tau, kGravity),
                            wm::forward_dynamics(model0, data0, q, nu, tau, kGravity)));
      EXPECT_TRUE(
          same_bits(wm::forward_dynamics(model, data, q, nu, tau, kGravity, std::span(&w, 1)),
                    wm::forward_dynamics(model0, data0, q, nu, tau, kGravity, std::span(&w, 1))));
    }
  }
}
