// The MJCF written by wbi::mjcf::write_mjcf, loaded by MuJoCo (libmujoco), is the
// same multibody as wbi's model: total mass, M(q) (mj_fullM) and the bias forces
// (qfrc_bias, at zero and at nonzero velocity, through mujoco_conventions.hpp) at
// 20 random states agree to 1e-7 relative (max |a − b| ≤ 1e-7 max |b|), with and
// without armature, and MuJoCo loads the file without an error or a warning.
// Skipped, with a message, when the build has no MuJoCo (WBI_WITH_MUJOCO).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <wbi/mjcf/mjcf.hpp>
#include <wbi/mjcf/mujoco_conventions.hpp>
#include <wbi/model/algorithms.hpp>

#include "test_support.hpp"

#ifdef WBI_WITH_MUJOCO
#include <mujoco/mujoco.h>
#endif

namespace {

namespace wm = wbi::model;
namespace wj = wbi::mjcf;

constexpr double kTol = 1e-7;
constexpr int kStates = 20;

struct Robot {
  std::string label;
  std::filesystem::path urdf;  // empty when ../shared is missing
  bool fixed_base = false;
  std::vector<std::string> welded;  // e.g. the child links of F/T sensors' fixed joints
  std::vector<std::string> frames;  // sites (IMU, F/T), and spheres for contacts
};

std::vector<Robot> robots() {
  std::vector<Robot> out{{"arm7", wbi::test::project_model("arm7.urdf"), true, {}, {}},
                         {"humanoid",
                          wbi::test::project_model("humanoid.urdf"),
                          false,
                          {"l_foot", "r_foot"},
                          {"imu_frame", "l_foot", "r_foot", "l_sole", "r_sole"}}};
  const auto shared = wbi::test::shared_models_dir();
  out.push_back({"iCub 3",
                 shared ? *shared / "iCubGenova09/model.urdf" : "",
                 false,
                 {"l_hip_3", "r_hip_3", "l_foot_front", "l_foot_rear", "r_foot_front",
                  "r_foot_rear", "l_shoulder_3", "r_shoulder_3"},
                 {"imu_frame", "l_hip_3", "l_foot_front", "r_foot_rear", "l_sole", "r_sole"}});
  out.push_back({"TALOS",
                 shared ? *shared / "talos/talos_reduced.urdf" : "",
                 false,
                 {"wrist_left_ft_link", "wrist_right_ft_link", "gripper_left_motor_single_link",
                  "gripper_right_motor_single_link"},
                 {"imu_link", "wrist_left_ft_link", "left_sole_link", "right_sole_link"}});
  return out;
}

// max |a − b| / max |b|
double rel_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

#ifdef WBI_WITH_MUJOCO

std::vector<std::string>& warnings() {
  static std::vector<std::string> list;
  return list;
}
void record_warning(const char* text) { warnings().emplace_back(text); }

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, MjModelDeleter>;
using DataPtr = std::unique_ptr<mjData, MjDataDeleter>;

// Loads MJCF text from memory (a virtual file system: no file is written).
ModelPtr load_mjcf(const std::string& xml, std::string& messages) {
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    messages = "cannot make the VFS file";
    return nullptr;
  }
  std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), name)], xml.data(), xml.size());
  char error[2000] = "";
  ModelPtr m(mj_loadXML(name, vfs.get(), error, sizeof(error)));
  mj_deleteVFS(vfs.get());
  messages = error;
  return m;
}

struct Errors {
  double mass = 0, M = 0, gravity = 0, bias = 0, site = 0, acceleration = 0;
};

// Loads the written model in MuJoCo and compares it with wbi's at kStates states.
Errors compare(const wm::Model& model, const wj::MjcfOptions& options, const std::string& what) {
  SCOPED_TRACE(what);
  Errors errors;
  const std::string xml = wj::write_mjcf(model, options);
  warnings().clear();
  mju_user_warning = record_warning;
  std::string messages;
  const ModelPtr m = load_mjcf(xml, messages);
  EXPECT_TRUE(m) << "mj_loadXML: " << messages;
  if (!m) {
    return errors;
  }
  EXPECT_EQ(messages, "") << "mj_loadXML reported a warning";
  EXPECT_EQ(m->nv, model.nv);
  EXPECT_EQ(m->nq, model.nq);
  const DataPtr d(mj_makeData(m.get()));

  errors.mass = std::abs(mj_getTotalmass(m.get()) - model.total_mass) / model.total_mass;
  EXPECT_LE(errors.mass, kTol) << "total mass " << mj_getTotalmass(m.get()) << " vs "
                               << model.total_mass;

  wj::MujocoIndex index;
  for (const std::string& joint : model.joint_name) {
    const int id = mj_name2id(m.get(), mjOBJ_JOINT, joint.c_str());
    EXPECT_GE(id, 0) << "joint " << joint << " missing in MuJoCo";
    if (id < 0) {
      return errors;
    }
    index.qpos.push_back(m->jnt_qposadr[id]);
    index.dof.push_back(m->jnt_dofadr[id]);
  }

  wm::Data data(model);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Vector3d g(m->opt.gravity[0], m->opt.gravity[1], m->opt.gravity[2]);
  const auto nv = static_cast<Eigen::Index>(model.nv);
  Eigen::Map<Eigen::VectorXd> qpos(d->qpos, m->nq);
  Eigen::Map<Eigen::VectorXd> qvel(d->qvel, m->nv);
  Eigen::Map<const Eigen::VectorXd> bias_mj(d->qfrc_bias, m->nv);
  Eigen::MatrixXd M_mj(nv, nv), M(nv, nv);
  Eigen::VectorXd h(nv), nu(nv);
  for (int s = 0; s < kStates; ++s) {
    const Eigen::VectorXd q = wm::random_configuration(model, rng);
    for (Eigen::Index k = 0; k < nv; ++k) {
      nu[k] = 2.0 * unit(rng);
    }
    wj::wbi_q_to_mujoco_qpos(model, index, q, qpos);
    qvel.setZero();
    mj_forward(m.get(), d.get());
    mj_fullM(m.get(), M_mj.data(), d->qM);  // symmetric: row- or column-major alike
    wj::mujoco_mass_matrix_to_wbi(model, index, q, M_mj, M);
    // the armature is the model's (Model::joint_armature), written by the MJCF
    errors.M = std::max(errors.M, rel_error(M, wm::mass_matrix(model, data, q)));
    wj::mujoco_force_to_wbi(model, index, q, bias_mj, h);
    errors.gravity = std::max(errors.gravity, rel_error(h, wm::gravity_forces(model, data, q, g)));

    wj::wbi_nu_to_mujoco_qvel(model, index, q, nu, qvel);
    mj_forward(m.get(), d.get());
    wj::mujoco_force_to_wbi(model, index, q, bias_mj, h);
    errors.bias = std::max(errors.bias, rel_error(h, wm::bias_forces(model, data, q, nu, g)));

    // forward dynamics under generalized forces (base wrench included): qacc = T ν̇,
    // with no Ṫν term (armature included). Only without damping and friction loss,
    // which wbi's ABA does not model and MuJoCo adds as passive and constraint forces.
    if (options.damping.empty() && options.frictionloss.empty()) {
      Eigen::VectorXd tau(nv), dnu(nv);
      for (Eigen::Index k = 0; k < nv; ++k) {
        tau[k] = 20.0 * unit(rng);
      }
      Eigen::Map<Eigen::VectorXd> applied(d->qfrc_applied, m->nv);
      wj::wbi_force_to_mujoco(model, index, q, tau, applied);
      mj_forward(m.get(), d.get());
      wj::mujoco_qvel_to_wbi_nu(model, index, q, Eigen::Map<const Eigen::VectorXd>(d->qacc, m->nv),
                                dnu);
      errors.acceleration = std::max(
          errors.acceleration, rel_error(dnu, wm::forward_dynamics(model, data, q, nu, tau, g)));
      applied.setZero();
    }

    // every site where wbi puts its frame (the frame's pose composed with the site's)
    wm::forward_kinematics(model, data, q);
    for (const wj::Site& site : options.sites) {
      const int id = mj_name2id(m.get(), mjOBJ_SITE, site.name.c_str());
      const Eigen::Matrix4d X = wm::frame_pose(model, data, model.frame_id(site.frame));
      const Eigen::Vector3d p = X.topRightCorner<3, 1>() + X.topLeftCorner<3, 3>() * site.position;
      const Eigen::Matrix3d R = X.topLeftCorner<3, 3>() * site.rotation;
      const Eigen::Map<const Eigen::Vector3d> p_mj(d->site_xpos + 3 * id);
      const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> R_mj(d->site_xmat +
                                                                                9 * id);
      errors.site = std::max(
          {errors.site, (p_mj - p).cwiseAbs().maxCoeff(), (R_mj - R).cwiseAbs().maxCoeff()});
    }
  }
  EXPECT_LE(errors.site, 1e-12) << "site poses";
  EXPECT_LE(errors.M, kTol) << "M";
  EXPECT_LE(errors.gravity, kTol) << "bias at zero velocity (gravity)";
  EXPECT_LE(errors.bias, kTol) << "bias at nonzero velocity";
  EXPECT_LE(errors.acceleration, kTol) << "forward dynamics";
  for (int w = 0; w < mjNWARNING; ++w) {
    EXPECT_EQ(d->warning[w].number, 0) << "MuJoCo warning " << w;
  }
  EXPECT_TRUE(warnings().empty()) << "MuJoCo warned: " << warnings().front();
  mju_user_warning = nullptr;
  std::cout << "[ measured ] " << what << ": mass " << errors.mass << ", M " << errors.M
            << ", gravity " << errors.gravity << ", bias (nonzero velocity) " << errors.bias
            << ", forward dynamics " << errors.acceleration << ", site poses " << errors.site
            << " m|rad\n";
  return errors;
}

wm::Model load(const Robot& robot, const std::map<std::string, double>& armature = {}) {
  wm::LoadOptions load;
  load.fixed_base = robot.fixed_base;
  load.repair_inertia = true;
  load.armature = armature;
  return wm::load_urdf_file(robot.urdf.string(), load);
}

// Armature of the order of real actuators: 0.01 … 0.5 kg m², by joint name.
std::map<std::string, double> some_armature(const wm::Model& model) {
  std::map<std::string, double> armature;
  for (int k = 0; k < model.n_joints; ++k) {
    armature[model.joint_name[static_cast<std::size_t>(k)]] =
        0.01 + 0.49 * static_cast<double>(k % 7) / 6.0;
  }
  return armature;
}

class MujocoAgreement : public ::testing::TestWithParam<int> {};

TEST_P(MujocoAgreement, MassMatrixAndBiasForcesMatchTheModelLibrary) {
  const Robot robot = robots()[static_cast<std::size_t>(GetParam())];
  if (robot.urdf.empty()) {
    GTEST_SKIP() << wbi::test::kSharedMissing << " (expected "
                 << (wbi::test::source_dir().parent_path() / "shared" / "models").string() << ")";
  }
  const wm::Model model = load(robot);
  wj::MjcfOptions options;
  compare(model, options, robot.label + ", no armature");
  // the model's armature, written by the MJCF: forward dynamics agree too
  const wm::Model armed = load(robot, some_armature(model));
  compare(armed, options, robot.label + ", armature");
  // damping and friction loss enter neither M nor the bias forces
  options.damping.assign(static_cast<std::size_t>(model.n_joints), 0.3);
  options.frictionloss.assign(static_cast<std::size_t>(model.n_joints), 0.2);
  compare(armed, options, robot.label + ", armature, damping, friction loss");
  options.inertia_form = wj::InertiaForm::kFull;
  compare(armed, options, robot.label + ", fullinertia");
}

// Welded links (bodies of their own), sites on sensor frames, contact geometry and
// a ground: the dynamics are the same, the sites sit on wbi's frames, and MuJoCo
// has one body more per welded link.
TEST_P(MujocoAgreement, WeldedLinksSitesAndContactsKeepTheDynamics) {
  const Robot robot = robots()[static_cast<std::size_t>(GetParam())];
  if (robot.urdf.empty()) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  const wm::Model model = load(robot, some_armature(load(robot)));
  wj::MjcfOptions options;
  options.welded_links = robot.welded;
  options.ground.enabled = true;
  options.ground.height = -2.0;  // below every random configuration: no contact
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const std::string& frame : robot.frames) {
    options.sites.push_back({frame + "_site", frame, Eigen::Vector3d(0.01, -0.02, 0.03), tilt});
    wj::ContactGeometry box;
    box.link = frame;
    box.size = {0.1, 0.05, 0.01};
    box.position = {0.0, 0.0, -0.005};
    options.contacts.push_back(box);
  }
  compare(model, options, robot.label + ", welded links, sites, contacts");

  std::string messages;
  const ModelPtr m = load_mjcf(wj::write_mjcf(model, options), messages);
  ASSERT_TRUE(m) << messages;
  // MuJoCo's world body, the model's bodies (a fixed root named "world" is MuJoCo's
  // world body, its mass on a body "world_inertial"), one per welded link
  const bool massless_world_root = model.body_name[0] == "world" && model.body_mass[0] <= 0.0;
  EXPECT_EQ(m->nbody, 1 + model.n_bodies + static_cast<int>(robot.welded.size()) -
                          (massless_world_root ? 1 : 0));
  EXPECT_EQ(m->ngeom, static_cast<int>(robot.frames.size()) + 1);
  EXPECT_EQ(m->nsite, static_cast<int>(robot.frames.size()));
}

std::string robot_name(const ::testing::TestParamInfo<int>& param) {
  const char* const kNames[] = {"arm7", "humanoid", "iCub3", "TALOS"};
  return kNames[param.param];
}

// F/T across a lumped fixed joint, by the welded_links design: on a fixed-base iCub 3
// at rest, MuJoCo's force/torque sensors at sites on the welded child links of the
// F/T sensor joints read the weight of everything below the joint (mass and CoM
// from wbi's model) — the wrench the parent exerts on the child, about the site, in
// site axes — and an IMU site on the root reads the proper acceleration +g.
TEST(MujocoSensors, ForceTorqueAcrossWeldedLinksAndImuAtRest) {
  const auto shared = wbi::test::shared_models_dir();
  if (!shared) {
    GTEST_SKIP() << wbi::test::kSharedMissing;
  }
  wm::LoadOptions load;
  load.fixed_base = true;
  const wm::Model model = wm::load_urdf_file((*shared / "iCubGenova09/model.urdf").string(), load);
  const std::vector<std::string> sensed{"l_hip_3", "r_foot_front", "l_foot_rear", "r_shoulder_3"};
  wj::MjcfOptions options;
  options.welded_links = sensed;
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(-1, 2, 0.5).normalized()).toRotationMatrix();
  for (const std::string& link : sensed) {
    options.sites.push_back({link + "_ft", link, Eigen::Vector3d(0.01, 0.02, -0.03), tilt,
                             wj::SiteSensor::kForceTorque});
  }
  options.sites.push_back(
      {"imu", "root_link", Eigen::Vector3d::Zero(), tilt, wj::SiteSensor::kImu});
  std::string messages;
  const ModelPtr m = load_mjcf(wj::write_mjcf(model, options), messages);
  ASSERT_TRUE(m) << messages;
  EXPECT_EQ(messages, "");
  const DataPtr d(mj_makeData(m.get()));
  wj::MujocoIndex index;
  for (const std::string& joint : model.joint_name) {
    const int id = mj_name2id(m.get(), mjOBJ_JOINT, joint.c_str());
    index.qpos.push_back(m->jnt_qposadr[id]);
    index.dof.push_back(m->jnt_dofadr[id]);
  }
  auto sensor = [&](const std::string& name) {
    const int id = mj_name2id(m.get(), mjOBJ_SENSOR, name.c_str());
    EXPECT_GE(id, 0) << name;
    return Eigen::Vector3d(Eigen::Map<const Eigen::Vector3d>(d->sensordata + m->sensor_adr[id]));
  };
  wm::Data data(model);
  std::mt19937 rng(3);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  double max_error = 0.0;
  for (int s = 0; s < 5; ++s) {
    const Eigen::VectorXd q = wm::random_configuration(model, rng);
    Eigen::Map<Eigen::VectorXd> qpos(d->qpos, m->nq);
    wj::wbi_q_to_mujoco_qpos(model, index, q, qpos);
    mju_zero(d->qvel, m->nv);
    mju_zero(d->qfrc_applied, m->nv);
    mj_forward(m.get(), d.get());
    // held at rest: the joints' torques balance gravity, so qacc = 0
    mju_copy(d->qfrc_applied, d->qfrc_bias, m->nv);
    mj_forward(m.get(), d.get());
    wm::forward_kinematics(model, data, q);
    for (const wj::Site& site : options.sites) {
      const int link = model.frame_id(site.frame);
      const Eigen::Matrix4d X = wm::frame_pose(model, data, link);
      const Eigen::Matrix3d R = X.topLeftCorner<3, 3>() * site.rotation;
      const Eigen::Vector3d p = X.topRightCorner<3, 1>() + X.topLeftCorner<3, 3>() * site.position;
      if (site.sensor == wj::SiteSensor::kImu) {
        max_error = std::max(max_error, (sensor("imu_accelerometer") - R.transpose() * -g).norm());
        continue;
      }
      // everything below the link: the frames whose parent chain reaches it
      double mass = 0.0;
      Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // Σ m_i c_i, world
      for (int f = 0; f < model.n_frames(); ++f) {
        int a = f;
        while (a >= 0 && a != link) {
          a = model.frame_parent[static_cast<std::size_t>(a)];
        }
        const wm::SpatialInertia& I = model.frame_inertia[static_cast<std::size_t>(f)];
        if (a != link || I.m <= 0.0) {
          continue;
        }
        const Eigen::Matrix4d X_WF = wm::frame_pose(model, data, f);
        const auto uf = static_cast<std::size_t>(f);
        const Eigen::Matrix3d R_WB = X_WF.topLeftCorner<3, 3>() * model.frame_R_BF[uf].transpose();
        const Eigen::Vector3d p_WB = X_WF.topRightCorner<3, 1>() - R_WB * model.frame_p_BF[uf];
        mass += I.m;
        moment += I.m * (p_WB + R_WB * (I.h / I.m));
      }
      const Eigen::Vector3d force = -mass * g;  // the parent holds the subtree up
      const Eigen::Vector3d torque = (moment / mass - p).cross(force);
      max_error =
          std::max({max_error, (sensor(site.name + "_force") - R.transpose() * force).norm(),
                    (sensor(site.name + "_torque") - R.transpose() * torque).norm()});
    }
  }
  std::cout << "[ measured ] F/T and IMU at rest, max error " << max_error << " (N, N m, m/s^2)\n";
  EXPECT_LE(max_error, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(Robots, MujocoAgreement, ::testing::Range(0, 4), robot_name);

#else

TEST(MujocoAgreement, Skipped) {
  GTEST_SKIP() << "MuJoCo not found at configure time (libmujoco-dev; "
                  "scripts/install-deps installs it)";
}

#endif

}  // namespace
