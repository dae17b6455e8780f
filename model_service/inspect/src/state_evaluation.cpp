// The evaluation of a JSON state (state_evaluation.hpp): the state is checked and
// turned into (q, ν, gravity) in the model's order, the backend computes, and the
// results are permuted into the caller's joint order.
#include <wbi/model_inspect/state_evaluation.hpp>

#include <cmath>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <wbi/model/configuration.hpp>

#include "eigen_json.hpp"

namespace wbi::model_inspect {

namespace {

using nlohmann::json;
namespace wm = wbi::model;

std::string read_text(const std::string& where) {
  std::ostringstream text;
  if (where == "-") {
    text << std::cin.rdbuf();
    return text.str();
  }
  std::ifstream in(where);
  if (!in) {
    throw std::runtime_error("state file '" + where + "': cannot open");
  }
  text << in.rdbuf();
  return text.str();
}

void check_keys(const json& state) {
  static const std::set<std::string> kKeys{
      "q",       "dq",     "base_position", "base_quaternion", "base_velocity",
      "gravity", "frames", "joints"};
  for (const auto& [key, value] : state.items()) {
    if (kKeys.count(key) == 0) {
      throw std::runtime_error("state: unknown key '" + key + "'");
    }
  }
}

// state[key] as `size` numbers.
Eigen::VectorXd numbers(const json& state, const std::string& key, std::size_t size) {
  const json& v = state.at(key);
  if (!v.is_array() || v.size() != size) {
    throw std::runtime_error("state: '" + key + "' must be an array of " + std::to_string(size) +
                             " numbers" +
                             (v.is_array() ? ", got " + std::to_string(v.size()) : ""));
  }
  Eigen::VectorXd out(static_cast<Eigen::Index>(size));
  for (std::size_t i = 0; i < size; ++i) {
    if (!v[i].is_number()) {
      throw std::runtime_error("state: '" + key + "'[" + std::to_string(i) + "] is not a number");
    }
    out[static_cast<Eigen::Index>(i)] = v[i].get<double>();
  }
  return out;
}

// The caller's joints: their names, and order[k] = the model index of the
// caller's k-th joint. Without 'joints', the model's own order.
struct CallerJoints {
  std::vector<std::string> names;
  std::vector<int> order;
};

CallerJoints caller_joints(const wm::Model& m, const json& state) {
  CallerJoints joints;
  if (!state.contains("joints")) {
    for (int k = 0; k < m.n_joints; ++k) {
      joints.order.push_back(k);
      joints.names.push_back(m.joint_name[static_cast<std::size_t>(k)]);
    }
    return joints;
  }
  std::set<std::string> seen;
  for (const auto& j : state["joints"]) {
    if (!j.is_string()) {
      throw std::runtime_error("state: 'joints' must be an array of joint names");
    }
    const std::string name = j.get<std::string>();
    if (!m.has_joint(name)) {
      throw std::runtime_error("state: unknown joint '" + name + "' in 'joints'");
    }
    if (!seen.insert(name).second) {
      throw std::runtime_error("state: joint '" + name + "' appears twice in 'joints'");
    }
    joints.order.push_back(m.joint_id(name));
    joints.names.push_back(name);
  }
  if (joints.order.size() != static_cast<std::size_t>(m.n_joints)) {
    for (const auto& name : m.joint_name) {
      if (seen.count(name) == 0) {
        throw std::runtime_error("state: 'joints' must list every joint of the model; '" + name +
                                 "' is missing");
      }
    }
  }
  return joints;
}

struct ModelState {
  Eigen::VectorXd q;
  Eigen::VectorXd nu;
  Eigen::Vector3d gravity;
};

// q, ν and gravity in the model's order, from the state in the caller's order.
ModelState model_state(const wm::Model& m, const json& state, const std::vector<int>& order) {
  const auto n = static_cast<std::size_t>(m.n_joints);
  const Eigen::VectorXd s =
      state.contains("q") ? numbers(state, "q", n) : Eigen::VectorXd::Zero(m.n_joints);
  const Eigen::VectorXd ds =
      state.contains("dq") ? numbers(state, "dq", n) : Eigen::VectorXd::Zero(m.n_joints);
  ModelState out{wm::neutral_configuration(m), Eigen::VectorXd::Zero(m.nv),
                 Eigen::Vector3d(0.0, 0.0, -9.81)};
  if (state.contains("gravity")) {
    out.gravity = numbers(state, "gravity", 3);
  }
  for (const char* key : {"base_position", "base_quaternion", "base_velocity"}) {
    if (!m.floating_base && state.contains(key)) {
      throw std::runtime_error(std::string("state: '") + key +
                               "' given, but the model has a fixed base");
    }
  }
  if (m.floating_base) {
    if (state.contains("base_position")) {
      out.q.head<3>() = numbers(state, "base_position", 3);
    }
    if (state.contains("base_quaternion")) {
      const Eigen::VectorXd quat = numbers(state, "base_quaternion", 4);
      if (std::abs(quat.norm() - 1.0) > 1e-6) {
        throw std::runtime_error("state: 'base_quaternion' [w,x,y,z] has norm " +
                                 std::to_string(quat.norm()) + ", expected a unit quaternion");
      }
      out.q.segment<4>(3) = quat;
    }
    if (state.contains("base_velocity")) {
      out.nu.head<6>() = numbers(state, "base_velocity", 6);
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const auto mk = static_cast<std::size_t>(order[k]);
    out.q[m.joint_q_index[mk]] = s[static_cast<Eigen::Index>(k)];
    out.nu[m.joint_v_index[mk]] = ds[static_cast<Eigen::Index>(k)];
  }
  return out;
}

// ν in the caller's order: perm[c] = the model's ν index of the caller's ν index c.
class CallerOrder {
 public:
  CallerOrder(const wm::Model& m, const std::vector<int>& order) {
    for (int b = 0; b < m.base_nv; ++b) {
      perm_.push_back(b);
    }
    for (const int mk : order) {
      perm_.push_back(m.joint_v_index[static_cast<std::size_t>(mk)]);
    }
  }

  Eigen::VectorXd vector(const Eigen::VectorXd& a) const {
    Eigen::VectorXd r(size());
    for (Eigen::Index c = 0; c < size(); ++c) {
      r[c] = a[at(c)];
    }
    return r;
  }

  Eigen::MatrixXd columns(const Eigen::MatrixXd& a) const {
    Eigen::MatrixXd r(a.rows(), size());
    for (Eigen::Index c = 0; c < size(); ++c) {
      r.col(c) = a.col(at(c));
    }
    return r;
  }

  Eigen::MatrixXd rows_and_columns(const Eigen::MatrixXd& a) const {
    const Eigen::MatrixXd cols = columns(a);
    Eigen::MatrixXd r(size(), size());
    for (Eigen::Index row = 0; row < size(); ++row) {
      r.row(row) = cols.row(at(row));
    }
    return r;
  }

 private:
  Eigen::Index size() const { return static_cast<Eigen::Index>(perm_.size()); }
  Eigen::Index at(Eigen::Index c) const { return perm_[static_cast<std::size_t>(c)]; }

  std::vector<int> perm_;
};

}  // namespace

json read_state(const std::string& where) {
  const std::string text = read_text(where);
  try {
    json state = json::parse(text);
    if (!state.is_object()) {
      throw std::runtime_error("state '" + where + "': expected a JSON object");
    }
    return state;
  } catch (const json::parse_error& e) {
    throw std::runtime_error("state '" + where + "': JSON error: " + e.what());
  }
}

json evaluate_state(wm::ModelBackend& backend, const json& state) {
  const wm::Model& m = backend.model();
  check_keys(state);
  const CallerJoints joints = caller_joints(m, state);
  const ModelState x = model_state(m, state, joints.order);
  const CallerOrder caller(m, joints.order);
  json out;
  out["joints"] = joints.names;
  out["mass_matrix"] = detail::rows_json(caller.rows_and_columns(backend.mass_matrix(x.q)));
  out["bias_forces"] =
      detail::vector_json(caller.vector(backend.bias_forces(x.q, x.nu, x.gravity)));
  out["gravity_forces"] =
      detail::vector_json(caller.vector(backend.gravity_forces(x.q, x.gravity)));
  out["total_mass"] = m.total_mass;
  out["com"] =
      m.total_mass > 0.0 ? detail::vector_json(backend.center_of_mass(x.q)) : json(nullptr);
  out["centroidal_momentum"] = m.total_mass > 0.0
                                   ? detail::vector_json(backend.centroidal_momentum(x.q, x.nu))
                                   : json(nullptr);
  out["backend"] = std::string(backend.name());
  out["frames"] = json::object();
  if (state.contains("frames")) {
    for (const auto& f : state["frames"]) {
      if (!f.is_string()) {
        throw std::runtime_error("state: 'frames' must be an array of frame names");
      }
      const std::string name = f.get<std::string>();
      if (!m.has_frame(name)) {
        throw std::runtime_error("state: unknown frame '" + name + "'");
      }
      const int id = m.frame_id(name);
      json frame;
      frame["transform"] = detail::rows_json(backend.frame_pose(x.q, id));
      frame["jacobian"] = detail::rows_json(caller.columns(backend.frame_jacobian(x.q, id)));
      frame["dJnu"] = detail::vector_json(backend.frame_bias_acceleration(x.q, x.nu, id));
      out["frames"][name] = frame;
    }
  }
  return out;
}

}  // namespace wbi::model_inspect
