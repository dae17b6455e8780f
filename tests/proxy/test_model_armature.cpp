// Armature through the proxy: the local model (DdsInterfaceOptions::armature)
// and the remote model (the model_service component's `armature` parameter, or
// the joints of its `robot_config` file, here in this process, answering over
// DDS request/reply) agree over a joint
// subset, and both really carry the armature: M grows by it on the diagonal of
// the controlled joints and inverse dynamics by armature · q̈.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <wbi/model_service/component.hpp>
#include <wbi/runtime/runner.hpp>

#include "remote_model_peer.hpp"

namespace {

using namespace wbi::test;

const std::map<std::string, double> kArmature{
    {"joint_1", 0.31}, {"joint_2", 0.27},  {"joint_3", 0.12}, {"joint_4", 0.09},
    {"joint_5", 0.05}, {"joint_6", 0.021}, {"joint_7", 0.013}};

// kArmature as a YAML block map: "joint: value" (the service's armature
// parameter) or "joint: {armature: value}" (a robot config's joints).
std::string armature_yaml(bool robot_config_joints) {
  std::string yaml;
  for (const auto& [joint, value] : kArmature) {
    const std::string number = std::to_string(value);
    yaml +=
        "  " + joint + ": " + (robot_config_joints ? "{armature: " + number + "}" : number) + "\n";
  }
  return yaml;
}

// The model service (with `service_parameters`) and a local model with
// kArmature agree, and both carry it.
void expect_local_and_remote_agree(const std::string& robot,
                                   const std::string& service_parameters) {
  ArmPeer peer(robot);
  wbi::dds::Participant service_side("service");
  wbi::runtime::SystemClock clock;
  wbi::runtime::ComponentRunner service(
      std::make_unique<wbi::model_service::ModelServiceComponent>(),
      wbi::runtime::ComponentContext{"model", "model_service", &service_side, &clock});
  service.configure(
      wbi::runtime::Parameters::from_string(service_parameters + "robot: " + robot + "\n"));
  service.activate();

  const wbi::IdList joints{"joint_4", "joint_2", "joint_6"};
  auto local_options = arm_options(robot);
  local_options.armature = kArmature;  // the non-controlled joints' entries have no effect
  auto local = connect(local_options, joints);
  auto plain = connect(arm_options(robot), joints);
  auto remote = connect(remote_options(robot), joints);
  const int n = 3;

  const Eigen::Vector3d q(0.3, -0.4, 0.7), dq(0.5, -1.0, 2.0), ddq(1.0, 2.0, -3.0);
  const wbi::Transform world_H_base = wbi::Transform::Identity();
  const Eigen::Matrix<double, 6, 1> zero6 = Eigen::Matrix<double, 6, 1>::Zero();
  const Eigen::Vector3d gravity(0, 0, -9.81);
  const double tol = 1e-9;
  const auto both = [&](auto&& f) {
    auto a = f(*local);
    auto b = f(*remote);
    EXPECT_TRUE(a.isApprox(b, tol) || (a - b).norm() < tol) << "local\n" << a << "\nremote\n" << b;
    return a;
  };
  const auto mass_matrix = [&](wbi::WholeBodyInterface& r) {
    Eigen::MatrixXd M(6 + n, 6 + n);
    r.mass_matrix(q, world_H_base, M);
    return M;
  };
  const auto inverse_dynamics = [&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd tau(6 + n);
    r.inverse_dynamics(q, world_H_base, dq, zero6, ddq, zero6, gravity, tau);
    return tau;
  };
  const Eigen::MatrixXd M = both(mass_matrix);
  const Eigen::VectorXd tau = both(inverse_dynamics);
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd h(6 + n);
    r.bias_forces(q, world_H_base, dq, zero6, gravity, h);
    return h;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::VectorXd g(6 + n);
    r.gravity_forces(q, world_H_base, gravity, g);
    return g;
  });
  both([&](wbi::WholeBodyInterface& r) {
    Eigen::MatrixXd A(6, 6 + n);
    r.centroidal_momentum_matrix(q, world_H_base, A);
    return A;
  });

  // Against the model without armature: exactly the diagonal, and armature · q̈.
  Eigen::MatrixXd expected_dM = Eigen::MatrixXd::Zero(6 + n, 6 + n);
  Eigen::VectorXd expected_dtau = Eigen::VectorXd::Zero(6 + n);
  for (int k = 0; k < n; ++k) {
    const double a = kArmature.at(joints[static_cast<std::size_t>(k)]);
    expected_dM(6 + k, 6 + k) = a;
    expected_dtau[6 + k] = a * ddq[k];
  }
  EXPECT_TRUE((M - mass_matrix(*plain) - expected_dM).isZero(1e-12)) << M - mass_matrix(*plain);
  EXPECT_TRUE((tau - inverse_dynamics(*plain) - expected_dtau).isZero(1e-12))
      << tau - inverse_dynamics(*plain);

  service.deactivate();
  service.shutdown();
}

TEST(ModelArmature, LocalAndRemoteModelsAgree) {
  expect_local_and_remote_agree("arm_armature", "urdf: " + project_model("arm7.urdf").string() +
                                                    "\narmature:\n" + armature_yaml(false));
}

// robot_config: the simulation's file gives the service its URDF and armature.
TEST(ModelArmature, RobotConfigGivesTheServiceItsArmature) {
  const auto file = std::filesystem::path(testing::TempDir()) / "model_armature_robot.yaml";
  {
    std::ofstream out(file);
    out << "urdf: " << project_model("arm7.urdf").string() << "\nfixed_base: true\njoints:\n"
        << armature_yaml(true);
  }
  expect_local_and_remote_agree("arm_armature_config", "robot_config: " + file.string() + "\n");
  std::filesystem::remove(file);
}

TEST(ModelArmature, BadRobotConfigFailsConfigureNamingTheFileAndKey) {
  wbi::dds::Participant service_side("service");
  wbi::runtime::SystemClock clock;
  const auto file = std::filesystem::path(testing::TempDir()) / "model_armature_bad.yaml";
  {
    std::ofstream out(file);
    out << "urdf: " << project_model("arm7.urdf").string() << "\njoints: {joint_2: {armture: 1}}\n";
  }
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"robot_config: " + file.string(),
       {"robot_config", "model_armature_bad.yaml:2", "armture", "unknown key"}},
      {"robot_config: /nonexistent/robot.yaml", {"robot_config", "/nonexistent/robot.yaml"}},
      {"robot_config: " + file.string() + "\nurdf: " + project_model("arm7.urdf").string(),
       {"urdf", "not both"}},
  };
  for (const auto& [yaml, words] : cases) {
    wbi::runtime::ComponentRunner service(
        std::make_unique<wbi::model_service::ModelServiceComponent>(),
        wbi::runtime::ComponentContext{"model", "model_service", &service_side, &clock});
    EXPECT_THROW(service.configure(wbi::runtime::Parameters::from_string(yaml)),
                 wbi::runtime::TransitionError)
        << yaml;
    for (const std::string& word : words) {
      EXPECT_NE(service.last_error().find(word), std::string::npos)
          << yaml << ": " << service.last_error();
    }
  }
  std::filesystem::remove(file);
}

TEST(ModelArmature, BadArmatureFailsConfigureNamingTheParameterAndJoint) {
  wbi::dds::Participant service_side("service");
  wbi::runtime::SystemClock clock;
  const std::string urdf = "urdf: " + project_model("arm7.urdf").string() + "\n";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"armature: {elbow: 0.1}", {"armature", "unknown joint 'elbow'"}},
      {"armature: {joint_2: -1}", {"armature", "joint_2", "-1"}},
      {"armature: {joint_2: heavy}", {"armature", "entry 'joint_2'", "must be a number"}},
      {"armature: [0.1]", {"armature", "map of names to numbers"}},
  };
  for (const auto& [yaml, words] : cases) {
    wbi::runtime::ComponentRunner service(
        std::make_unique<wbi::model_service::ModelServiceComponent>(),
        wbi::runtime::ComponentContext{"model", "model_service", &service_side, &clock});
    EXPECT_THROW(service.configure(wbi::runtime::Parameters::from_string(urdf + yaml)),
                 wbi::runtime::TransitionError)
        << yaml;
    for (const std::string& word : words) {
      EXPECT_NE(service.last_error().find(word), std::string::npos)
          << yaml << ": " << service.last_error();
    }
  }
}

TEST(ModelArmature, LocalModelRejectsAnUnknownJoint) {
  ArmPeer peer("arm_armature_bad");
  auto options = arm_options("arm_armature_bad");
  options.armature = {{"elbow", 0.1}};
  auto robot = wbi::make_dds_interface(options);
  robot->add_joints({"joint_1"});
  try {
    robot->init(20s);
    FAIL() << "no error";
  } catch (const wbi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("elbow"), std::string::npos) << e.what();
  }
}

}  // namespace
