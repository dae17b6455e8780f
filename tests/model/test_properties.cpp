// Physical and mathematical properties of the algorithms, on the project's
// models and on every model of ../shared/models:
//   M symmetric positive definite; RNEA(ν̇) = Mν̇ + h; G = RNEA(q, 0, 0);
//   ABA inverts RNEA (to 1e-9); external wrenches enter as −Jᵀw in both;
//   frame Jacobians and J̇ν match finite differences; νᵀ(Ṁ − 2C)ν = 0 with
//   Ṁ by finite differences; A_G ν = centroidal momentum = Σ body momenta;
//   CoM Jacobian and J̇_com ν match finite differences;
//   an unforced free-floating robot conserves energy and momentum.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "model_test_common.hpp"

namespace wm = wbi::model;
using wbi::test::near_rel;

namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);

std::vector<std::filesystem::path> all_models() {
  auto v = wbi::test::project_models();
  for (const auto& p : wbi::test::shared_models()) {
    v.push_back(p);
  }
  return v;
}

struct Sample {
  Eigen::VectorXd q, nu, dnu;
};

Sample random_sample(const wm::Model& model, std::mt19937& rng) {
  return {wm::random_configuration(model, rng), wbi::test::random_vector(model.nv, rng, 1.5),
          wbi::test::random_vector(model.nv, rng, 1.5)};
}

}  // namespace

TEST(Properties, MassMatrixSymmetricPositiveDefinite) {
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(1);
    for (int t = 0; t < 3; ++t) {
      const Eigen::MatrixXd M = wm::mass_matrix(model, data, random_sample(model, rng).q);
      EXPECT_EQ((M - M.transpose()).cwiseAbs().maxCoeff(), 0.0) << "M not exactly symmetric";
      const double lambda_min =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff();
      EXPECT_GT(lambda_min, 0.0);
    }
  }
}

TEST(Properties, InverseDynamicsIsMassMatrixPlusBias) {
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(2);
    for (int t = 0; t < 3; ++t) {
      const Sample s = random_sample(model, rng);
      const Eigen::MatrixXd M = wm::mass_matrix(model, data, s.q);
      const Eigen::VectorXd h = wm::bias_forces(model, data, s.q, s.nu, kGravity);
      const Eigen::VectorXd G = wm::gravity_forces(model, data, s.q, kGravity);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.nv);
      EXPECT_TRUE(near_rel(wm::inverse_dynamics(model, data, s.q, s.nu, s.dnu, kGravity),
                           M * s.dnu + h, 1e-9));
      EXPECT_TRUE(near_rel(wm::inverse_dynamics(model, data, s.q, zero, zero, kGravity), G, 1e-9));
      // C(q,ν)ν is quadratic in ν and G does not depend on ν
      EXPECT_TRUE(near_rel(wm::bias_forces(model, data, s.q, 2.0 * s.nu, kGravity) - G,
                           4.0 * (h - G), 1e-9));
    }
  }
}

TEST(Properties, ForwardDynamicsInvertsInverseDynamics) {
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(3);
    for (int t = 0; t < 3; ++t) {
      const Sample s = random_sample(model, rng);
      const Eigen::VectorXd tau = wm::inverse_dynamics(model, data, s.q, s.nu, s.dnu, kGravity);
      EXPECT_TRUE(
          near_rel(wm::forward_dynamics(model, data, s.q, s.nu, tau, kGravity), s.dnu, 1e-9));
      // and agrees with M⁻¹(τ − h)
      const Eigen::MatrixXd M = wm::mass_matrix(model, data, s.q);
      const Eigen::VectorXd h = wm::bias_forces(model, data, s.q, s.nu, kGravity);
      const Eigen::VectorXd tau2 = wbi::test::random_vector(model.nv, rng, 3.0);
      EXPECT_TRUE(near_rel(wm::forward_dynamics(model, data, s.q, s.nu, tau2, kGravity),
                           M.ldlt().solve(tau2 - h), 1e-7));
    }
  }
}

TEST(Properties, ExternalWrenchesEnterAsJacobianTranspose) {
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(4);
    const Sample s = random_sample(model, rng);
    std::vector<wm::ExternalWrench> wrenches(2);
    wrenches[0].frame = model.n_frames() - 1;
    wrenches[1].frame = model.n_frames() / 2;
    Eigen::VectorXd JTw = Eigen::VectorXd::Zero(model.nv);
    wm::forward_kinematics(model, data, s.q);
    for (auto& w : wrenches) {
      w.wrench = wbi::test::random_vector(6, rng, 10.0);
      JTw += wm::frame_jacobian(model, data, w.frame).transpose() * w.wrench;
    }
    const Eigen::VectorXd tau0 = wm::inverse_dynamics(model, data, s.q, s.nu, s.dnu, kGravity);
    const Eigen::VectorXd tau =
        wm::inverse_dynamics(model, data, s.q, s.nu, s.dnu, kGravity, wrenches);
    EXPECT_TRUE(near_rel(tau, tau0 - JTw, 1e-9));
    EXPECT_TRUE(near_rel(wm::forward_dynamics(model, data, s.q, s.nu, tau, kGravity, wrenches),
                         s.dnu, 1e-9));
  }
}

TEST(Properties, JacobiansMatchFiniteDifferences) {
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(5);
    const Sample s = random_sample(model, rng);
    const double eps = 1e-6;
    const Eigen::VectorXd qp = wm::integrate(model, s.q, s.nu, eps);
    const Eigen::VectorXd qm = wm::integrate(model, s.q, s.nu, -eps);
    for (int f = 0; f < model.n_frames(); f += std::max(1, model.n_frames() / 25)) {
      SCOPED_TRACE(model.frame_name[static_cast<std::size_t>(f)]);
      wm::forward_velocity_kinematics(model, data, s.q, s.nu);
      const Eigen::VectorXd Jnu = wm::frame_jacobian(model, data, f) * s.nu;
      const Eigen::Matrix<double, 6, 1> dJnu = wm::frame_bias_acceleration(model, data, f);
      wm::forward_kinematics(model, data, qp);
      const Eigen::Matrix4d Hp = wm::frame_pose(model, data, f);
      const Eigen::VectorXd Jnu_p = wm::frame_jacobian(model, data, f) * s.nu;
      wm::forward_kinematics(model, data, qm);
      const Eigen::Matrix4d Hm = wm::frame_pose(model, data, f);
      const Eigen::VectorXd Jnu_m = wm::frame_jacobian(model, data, f) * s.nu;
      Eigen::Matrix<double, 6, 1> fd;
      fd.head<3>() = (Hp.topRightCorner<3, 1>() - Hm.topRightCorner<3, 1>()) / (2 * eps);
      fd.tail<3>() =
          wbi::test::rotation_log(Hp.topLeftCorner<3, 3>() * Hm.topLeftCorner<3, 3>().transpose()) /
          (2 * eps);
      EXPECT_TRUE(near_rel(Jnu, fd, 1e-6)) << "J";
      // constant ν (world-axis ω): d/dt (J ν) = J̇ ν
      EXPECT_TRUE(near_rel(dJnu, (Jnu_p - Jnu_m) / (2 * eps), 1e-6)) << "dJnu";
    }
  }
}

TEST(Properties, MassMatrixDerivativeMinusTwoCIsSkew) {
  // νᵀ(Ṁ − 2C)ν = 0 ⇔ νᵀṀν = 2νᵀ(h − G), Ṁ = dM/dt along ν (central differences)
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(6);
    for (int t = 0; t < 2; ++t) {
      const Sample s = random_sample(model, rng);
      const double eps = 1e-6;
      const Eigen::MatrixXd Mp = wm::mass_matrix(model, data, wm::integrate(model, s.q, s.nu, eps));
      const Eigen::MatrixXd Mm =
          wm::mass_matrix(model, data, wm::integrate(model, s.q, s.nu, -eps));
      const Eigen::MatrixXd Mdot = (Mp - Mm) / (2 * eps);
      const Eigen::VectorXd Cnu = wm::bias_forces(model, data, s.q, s.nu, kGravity) -
                                  wm::gravity_forces(model, data, s.q, kGravity);
      const double lhs = s.nu.dot(Mdot * s.nu);
      const double rhs = 2.0 * s.nu.dot(Cnu);
      EXPECT_NEAR(lhs, rhs, 1e-6 * std::max(1.0, std::abs(rhs)));
    }
  }
}

TEST(Properties, ChristoffelCoriolisMatrixMakesMdotMinus2CSkewFixedBase) {
  // Fixed base (q are coordinates): C_ij = Σ_k Γ_ijk q̇_k with
  // Γ_ijk = ½(∂M_ij/∂q_k + ∂M_ik/∂q_j − ∂M_jk/∂q_i), all ∂M by central differences.
  // Checks C q̇ = h − G and that Ṁ − 2C is skew-symmetric.
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    wm::LoadOptions options;
    options.fixed_base = true;
    const wm::Model model = wm::load_urdf_file(path.string(), options);
    wm::Data data(model);
    std::mt19937 rng(11);
    const Sample s = random_sample(model, rng);
    const int n = model.nv;
    const double eps = 1e-6;
    std::vector<Eigen::MatrixXd> dM(static_cast<std::size_t>(n));
    for (int k = 0; k < n; ++k) {
      Eigen::VectorXd qp = s.q, qm = s.q;
      qp[k] += eps;
      qm[k] -= eps;
      const Eigen::MatrixXd Mp = wm::mass_matrix(model, data, qp);
      dM[static_cast<std::size_t>(k)] = (Mp - wm::mass_matrix(model, data, qm)) / (2 * eps);
    }
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n), Mdot = Eigen::MatrixXd::Zero(n, n);
    for (int k = 0; k < n; ++k) {
      Mdot += dM[static_cast<std::size_t>(k)] * s.nu[k];
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) {
          C(i, j) +=
              0.5 *
              (dM[static_cast<std::size_t>(k)](i, j) + dM[static_cast<std::size_t>(j)](i, k) -
               dM[static_cast<std::size_t>(i)](j, k)) *
              s.nu[k];
        }
      }
    }
    const Eigen::VectorXd Cnu = wm::bias_forces(model, data, s.q, s.nu, kGravity) -
                                wm::gravity_forces(model, data, s.q, kGravity);
    EXPECT_TRUE(near_rel(C * s.nu, Cnu, 1e-6));
    const Eigen::MatrixXd N = Mdot - 2 * C;
    EXPECT_TRUE(near_rel(N + N.transpose(), Eigen::MatrixXd::Zero(n, n), 1e-6));
  }
}

TEST(Properties, CentroidalMomentumIsSumOfBodyMomenta) {
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(7);
    const Sample s = random_sample(model, rng);
    const Eigen::MatrixXd Ag = wm::centroidal_momentum_matrix(model, data, s.q);
    const Eigen::Matrix<double, 6, 1> hg = wm::centroidal_momentum(model, data, s.q, s.nu);
    EXPECT_TRUE(near_rel(Ag * s.nu, hg, 1e-9));
    // Σ over bodies: (m ċ_i, (c_i − c) × m ċ_i + R I_c Rᵀ ω_i), velocities from frame Jacobians
    const Eigen::Vector3d c = wm::center_of_mass(model, data, s.q);
    Eigen::Matrix<double, 6, 1> sum = Eigen::Matrix<double, 6, 1>::Zero();
    for (int b = 0; b < model.n_bodies; ++b) {
      const int f = model.frame_id(model.body_name[static_cast<std::size_t>(b)]);
      wm::forward_kinematics(model, data, s.q);
      const Eigen::Matrix4d H = wm::frame_pose(model, data, f);
      const Eigen::Matrix<double, 6, 1> V = wm::frame_jacobian(model, data, f) * s.nu;
      const Eigen::Matrix3d R = H.topLeftCorner<3, 3>();
      const Eigen::Vector3d ci =
          H.topRightCorner<3, 1>() + R * model.body_com[static_cast<std::size_t>(b)];
      const Eigen::Vector3d cdot = V.head<3>() + V.tail<3>().cross(ci - H.topRightCorner<3, 1>());
      const double m = model.body_mass[static_cast<std::size_t>(b)];
      sum.head<3>() += m * cdot;
      sum.tail<3>() +=
          (ci - c).cross(m * cdot) +
          R * model.body_inertia_c[static_cast<std::size_t>(b)] * R.transpose() * V.tail<3>();
    }
    EXPECT_TRUE(near_rel(hg, sum, 1e-9));
  }
}

TEST(Properties, CenterOfMassJacobianMatchesFiniteDifferences) {
  for (const auto& path : all_models()) {
    SCOPED_TRACE(path.string());
    const wm::Model model = wm::load_urdf_file(path.string());
    wm::Data data(model);
    std::mt19937 rng(8);
    const Sample s = random_sample(model, rng);
    const double eps = 1e-6;
    const Eigen::VectorXd qp = wm::integrate(model, s.q, s.nu, eps);
    const Eigen::VectorXd qm = wm::integrate(model, s.q, s.nu, -eps);
    const Eigen::MatrixXd Jc = wm::com_jacobian(model, data, s.q);
    const Eigen::Vector3d dJc = wm::com_bias_acceleration(model, data, s.q, s.nu);
    const Eigen::MatrixXd Ag = wm::centroidal_momentum_matrix(model, data, s.q);
    EXPECT_TRUE(near_rel(Jc, Ag.topRows<3>() / model.total_mass, 1e-9));
    const Eigen::Vector3d cp = wm::center_of_mass(model, data, qp);
    const Eigen::Vector3d cm = wm::center_of_mass(model, data, qm);
    EXPECT_TRUE(near_rel(Jc * s.nu, (cp - cm) / (2 * eps), 1e-6));
    const Eigen::Vector3d vp = wm::com_jacobian(model, data, qp) * s.nu;
    const Eigen::Vector3d vm = wm::com_jacobian(model, data, qm) * s.nu;
    EXPECT_TRUE(near_rel(dJc, (vp - vm) / (2 * eps), 1e-6));
  }
}

namespace {

// One RK4 step of (q, ν) under forward dynamics with τ = 0.
void rk4_step(const wm::Model& model, wm::Data& data, Eigen::VectorXd& q, Eigen::VectorXd& nu,
              double dt, const Eigen::Vector3d& gravity) {
  const Eigen::VectorXd tau = Eigen::VectorXd::Zero(model.nv);
  const Eigen::VectorXd a1 = wm::forward_dynamics(model, data, q, nu, tau, gravity);
  const Eigen::VectorXd v1 = nu;
  const Eigen::VectorXd v2 = nu + 0.5 * dt * a1;
  const Eigen::VectorXd a2 =
      wm::forward_dynamics(model, data, wm::integrate(model, q, v1, 0.5 * dt), v2, tau, gravity);
  const Eigen::VectorXd v3 = nu + 0.5 * dt * a2;
  const Eigen::VectorXd a3 =
      wm::forward_dynamics(model, data, wm::integrate(model, q, v2, 0.5 * dt), v3, tau, gravity);
  const Eigen::VectorXd v4 = nu + dt * a3;
  const Eigen::VectorXd a4 =
      wm::forward_dynamics(model, data, wm::integrate(model, q, v3, dt), v4, tau, gravity);
  q = wm::integrate(model, q, (v1 + 2 * v2 + 2 * v3 + v4) / 6.0, dt);
  nu += dt * (a1 + 2 * a2 + 2 * a3 + a4) / 6.0;
}

double energy(const wm::Model& model, wm::Data& data, const Eigen::VectorXd& q,
              const Eigen::VectorXd& nu, const Eigen::Vector3d& gravity) {
  const double T = 0.5 * nu.dot(wm::mass_matrix(model, data, q) * nu);
  return T - model.total_mass * gravity.dot(wm::center_of_mass(model, data, q));
}

void check_conservation(const std::filesystem::path& path) {
  SCOPED_TRACE(path.string());
  const wm::Model model = wm::load_urdf_file(path.string());
  ASSERT_TRUE(model.floating_base);
  wm::Data data(model);
  std::mt19937 rng(9);
  Eigen::VectorXd q = wm::random_configuration(model, rng);
  Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 0.5);
  // no gravity: energy, linear momentum and angular momentum about the CoM are constant
  const Eigen::Vector3d zero_g = Eigen::Vector3d::Zero();
  const double E0 = energy(model, data, q, nu, zero_g);
  const Eigen::Matrix<double, 6, 1> h0 = wm::centroidal_momentum(model, data, q, nu);
  for (int step = 0; step < 200; ++step) {
    rk4_step(model, data, q, nu, 1e-3, zero_g);
  }
  EXPECT_NEAR(energy(model, data, q, nu, zero_g), E0, 1e-6 * std::max(1.0, E0));
  EXPECT_TRUE(near_rel(wm::centroidal_momentum(model, data, q, nu), h0, 1e-6));
  // with gravity: total energy constant, horizontal linear momentum constant,
  // vertical momentum changes by m g t
  q = wm::random_configuration(model, rng);
  nu = wbi::test::random_vector(model.nv, rng, 0.5);
  const double E1 = energy(model, data, q, nu, kGravity);
  const Eigen::Matrix<double, 6, 1> h1 = wm::centroidal_momentum(model, data, q, nu);
  for (int step = 0; step < 200; ++step) {
    rk4_step(model, data, q, nu, 1e-3, kGravity);
  }
  EXPECT_NEAR(energy(model, data, q, nu, kGravity), E1, 1e-6 * std::max(1.0, std::abs(E1)));
  const Eigen::Matrix<double, 6, 1> h2 = wm::centroidal_momentum(model, data, q, nu);
  const double scale = std::max(1.0, h1.head<3>().norm());
  EXPECT_NEAR(h2[0], h1[0], 1e-6 * scale);
  EXPECT_NEAR(h2[1], h1[1], 1e-6 * scale);
  EXPECT_NEAR(h2[2], h1[2] + model.total_mass * kGravity.z() * 0.2, 1e-6 * scale);
}

}  // namespace

TEST(Properties, UnforcedFloatingRobotConservesEnergyAndMomentum) {
  if (std::filesystem::exists(wbi::test::project_model("humanoid.urdf"))) {
    check_conservation(wbi::test::project_model("humanoid.urdf"));
  }
  if (const auto dir = wbi::test::shared_models_dir()) {
    check_conservation(*dir / "iCubGenova09/model.urdf");
    check_conservation(*dir / "solo12/solo12.urdf");
  }
}

TEST(Properties, FixedBaseArmConservesEnergy) {
  for (const char* name : {"double_pendulum.urdf", "arm7.urdf"}) {
    const auto path = wbi::test::project_model(name);
    if (!std::filesystem::exists(path)) {
      continue;
    }
    SCOPED_TRACE(name);
    const wm::Model model = wm::load_urdf_file(path.string());
    ASSERT_FALSE(model.floating_base);
    wm::Data data(model);
    std::mt19937 rng(10);
    Eigen::VectorXd q = wm::random_configuration(model, rng);
    Eigen::VectorXd nu = wbi::test::random_vector(model.nv, rng, 0.5);
    const double E0 = energy(model, data, q, nu, kGravity);
    for (int step = 0; step < 200; ++step) {
      rk4_step(model, data, q, nu, 1e-3, kGravity);
    }
    EXPECT_NEAR(energy(model, data, q, nu, kGravity), E0, 1e-6 * std::max(1.0, std::abs(E0)));
  }
}
