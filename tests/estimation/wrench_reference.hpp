// What the F/T sensors of a robot read, computed independently of the
// estimator: the URDF is loaded a second time with every sensor joint made a
// revolute joint held at 0, so that each sensor's child side is a body of its
// own and the model's RNEA gives the wrench through it (its f_i).
#pragma once

#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "model_test_common.hpp"
#include "wbi/estimation/wrench_estimator.hpp"
#include "wbi/model/aba.hpp"
#include "wbi/model/configuration.hpp"
#include "wbi/model/rnea.hpp"
#include "wbi/model/urdf.hpp"

namespace wbi::test {

using estimation::ForceTorqueSensor;
using model::Vector6d;

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A state of the robot with known wrenches on some links, consistent with its
// dynamics: ν̇ from forward dynamics with random joint torques and no base torque.
struct DynamicState {
  Eigen::VectorXd q, nu, dnu, tau;  // tau [n_joints]
  std::vector<model::ExternalWrench> wrenches;
};

inline DynamicState random_state(const model::Model& m, const std::vector<std::string>& links,
                                 std::mt19937& rng, double wrench_scale = 100.0) {
  DynamicState s;
  model::Data data(m);
  s.q = model::random_configuration(m, rng);
  s.nu = random_vector(m.nv, rng, 1.0);
  Eigen::VectorXd tau = random_vector(m.nv, rng, 20.0);
  if (m.floating_base) {
    tau.head<6>().setZero();
  }
  for (const std::string& link : links) {
    Vector6d w;
    w << random_vector(3, rng, wrench_scale), random_vector(3, rng, 0.1 * wrench_scale);
    s.wrenches.push_back({m.frame_id(link), w});
  }
  s.dnu =
      model::forward_dynamics(m, data, s.q, s.nu, tau, Eigen::Vector3d(0, 0, -9.81), s.wrenches);
  s.tau = tau.tail(m.n_joints);
  return s;
}

// A robot at rest (ν = 0; ν̇ = 0 but the base's linear acceleration, by
// default 0 too) at a random configuration, with random wrenches on `links`
// and, on `balancing_link`, the wrench that holds it: the base needs no
// actuation, as on a floating-base robot.
inline DynamicState static_state(
    const model::Model& m, const std::vector<std::string>& links, const std::string& balancing_link,
    std::mt19937& rng, const Eigen::Vector3d& base_acceleration = Eigen::Vector3d::Zero()) {
  DynamicState s;
  model::Data data(m);
  s.q = model::random_configuration(m, rng);
  s.nu = Eigen::VectorXd::Zero(m.nv);
  s.dnu = Eigen::VectorXd::Zero(m.nv);
  s.dnu.head<3>() = base_acceleration;
  for (const std::string& link : links) {
    Vector6d w;
    w << random_vector(3, rng, 100.0), random_vector(3, rng, 10.0);
    s.wrenches.push_back({m.frame_id(link), w});
  }
  const Eigen::Vector3d gravity(0, 0, -9.81);
  model::inverse_dynamics(m, data, s.q, s.nu, s.dnu, gravity, s.wrenches);
  const Vector6d held = data.f[0];  // Σ inertial − Σ external, world origin: what is missing
  const int frame = m.frame_id(balancing_link);
  const int b = m.frame_body[frame];
  const Eigen::Vector3d p = data.p_WB[b] + data.R_WB[b] * m.frame_p_BF[frame];
  Vector6d w;
  w << held.head<3>(), held.tail<3>() - p.cross(held.head<3>());
  s.wrenches.push_back({frame, w});
  s.tau = model::inverse_dynamics(m, data, s.q, s.nu, s.dnu, gravity, s.wrenches).tail(m.n_joints);
  return s;
}

class SensorReference {
 public:
  SensorReference(const std::filesystem::path& urdf, std::vector<ForceTorqueSensor> sensors)
      : sensors_(std::move(sensors)), split_(split_model(urdf, sensors_)), data_(split_) {}

  // The readings (child on parent, sensor axes about the sensor origin) in state s
  // of model m (the unsplit one).
  std::vector<Vector6d> readings(const model::Model& m, const DynamicState& s) {
    Eigen::VectorXd q = Eigen::VectorXd::Zero(split_.nq);
    Eigen::VectorXd nu = Eigen::VectorXd::Zero(split_.nv);
    Eigen::VectorXd dnu = Eigen::VectorXd::Zero(split_.nv);
    q.head(m.base_nq) = s.q.head(m.base_nq);
    nu.head(m.base_nv) = s.nu.head(m.base_nv);
    dnu.head(m.base_nv) = s.dnu.head(m.base_nv);
    for (int k = 0; k < split_.n_joints; ++k) {
      if (m.has_joint(split_.joint_name[k])) {
        const int j = m.joint_id(split_.joint_name[k]);
        q[split_.joint_q_index[k]] = s.q[m.joint_q_index[j]];
        nu[split_.joint_v_index[k]] = s.nu[m.joint_v_index[j]];
        dnu[split_.joint_v_index[k]] = s.dnu[m.joint_v_index[j]];
      }
    }
    std::vector<model::ExternalWrench> wrenches;
    for (const auto& w : s.wrenches) {
      wrenches.push_back({split_.frame_id(m.frame_name[w.frame]), w.wrench});
    }
    model::inverse_dynamics(split_, data_, q, nu, dnu, Eigen::Vector3d(0, 0, -9.81), wrenches);
    std::vector<Vector6d> out;
    for (const ForceTorqueSensor& sensor : sensors_) {
      const int b = split_.joint_body[split_.joint_id(sensor.joint)];
      const Eigen::Matrix3d& R = data_.R_WB[b];
      const Eigen::Vector3d& p = data_.p_WB[b];
      const Vector6d& f = data_.f[b];  // parent on child, world origin
      Vector6d w;
      w << -(R.transpose() * f.head<3>()), -(R.transpose() * (f.tail<3>() - p.cross(f.head<3>())));
      out.push_back(w);
    }
    return out;
  }

 private:
  static model::Model split_model(const std::filesystem::path& urdf,
                                  const std::vector<ForceTorqueSensor>& sensors) {
    std::string text = read_text(urdf);
    for (const ForceTorqueSensor& sensor : sensors) {
      // <joint name="J" type="fixed"> → a revolute joint held at 0 (std::regex trips
      // GCC 12's maybe-uninitialized warning in the sanitizer build)
      const std::string fixed = "<joint name=\"" + sensor.joint + "\" type=\"fixed\">";
      const auto at = text.find(fixed);
      EXPECT_NE(at, std::string::npos) << "no fixed joint " << sensor.joint << " in " << urdf;
      if (at != std::string::npos) {
        text.replace(at, fixed.size(),
                     "<joint name=\"" + sensor.joint +
                         "\" type=\"revolute\"><axis xyz=\"0 0 1\"/><limit lower=\"-1\" "
                         "upper=\"1\" effort=\"1\" velocity=\"1\"/>");
      }
    }
    return model::load_urdf_string(text, {}, urdf.string() + " (sensor joints made revolute)");
  }

  std::vector<ForceTorqueSensor> sensors_;
  model::Model split_;
  model::Data data_;
};

}  // namespace wbi::test
