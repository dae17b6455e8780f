// `wbi model info|eval|bench|mjcf`: inspect a URDF, evaluate the model at a state
// given as JSON, time the algorithms, write it as MJCF. The work is in wbi::model
// and wbi::mjcf.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <wbi/mjcf/mjcf.hpp>
#include <wbi/model/algorithms.hpp>
#include <wbi/model/backend.hpp>
#include <wbi/mujoco_sim/robot_mjcf.hpp>
#include <wbi/robot_config/robot_config.hpp>

#include "../options.hpp"
#include "verbs.hpp"

namespace wbi::cli {

int run_model(Args args);

namespace {

namespace wm = wbi::model;
using nlohmann::json;

const char* const kModelUsage = "wbi model {info|eval|bench|mjcf} URDF [options]";
const char* const kModelHelp =
    "Inspect and evaluate robot models (rigid-body model library).\n"
    "\n"
    "sub-verbs:\n"
    "  info   joints with limits, frames, bodies after lumping, total mass, base kind\n"
    "  eval   evaluate M, h, G, CoM, centroidal momentum and frame quantities at a JSON state\n"
    "  bench  median ns per call of the main algorithms at random states\n"
    "  mjcf   write the model as MJCF, MuJoCo's XML, the same multibody to the last bit\n"
    "\n"
    "eval and bench take --backend wbi|dart: the dynamics library that computes (default wbi).\n"
    "All three take --armature JOINT=VALUE,...: per-joint rotor inertia (default 0).\n"
    "\n"
    "Run `wbi model SUBVERB --help` for the options of each.\n";

// "a,b,c" → {"a","b","c"}
std::vector<std::string> split_list(const std::string& text, const std::string& option = "joints",
                                    const std::string& what = "joint") {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) {
    if (item.empty()) {
      throw UsageError("--" + option + ": empty " + what + " name in '" + text + "'");
    }
    out.push_back(item);
  }
  if (out.empty()) {
    throw UsageError("--" + option + ": no " + what + " names given");
  }
  return out;
}

// "a=0.1,b=2e-3" → {a: 0.1, b: 0.002}; the values are checked by the loader.
std::map<std::string, double> parse_armature(const std::string& text) {
  std::map<std::string, double> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw UsageError("--armature: '" + item + "' is not JOINT=VALUE");
    }
    const std::string value = item.substr(eq + 1);
    std::size_t used = 0;
    double number = 0.0;
    try {
      number = std::stod(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (value.empty() || used != value.size()) {
      throw UsageError("--armature: the value of '" + item.substr(0, eq) + "' is not a number: '" +
                       value + "'");
    }
    if (!out.emplace(item.substr(0, eq), number).second) {
      throw UsageError("--armature: joint '" + item.substr(0, eq) + "' given twice");
    }
  }
  if (out.empty()) {
    throw UsageError("--armature: no JOINT=VALUE given");
  }
  return out;
}

const char* const kArmatureHelp =
    "rotor inertia reflected through the gear ratio, per joint: JOINT=VALUE,... [kg m^2 or kg] "
    "(added to the diagonal of M, MuJoCo's convention; default 0)";

wm::LoadOptions load_options(const Options& opts) {
  wm::LoadOptions options;
  options.fixed_base = opts.has("fixed-base");
  if (const auto joints = opts.get_optional("joints")) {
    options.joints = split_list(*joints);
  }
  if (const auto armature = opts.get_optional("armature")) {
    options.armature = parse_armature(*armature);
  }
  return options;
}

wm::Model load(const Options& opts) {
  try {
    return wm::load_urdf_file(opts.get("URDF"), load_options(opts));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

const char* const kBackendHelp =
    "dynamics library that computes: wbi (the project's own) or dart (DART 6, when built)";

// The model behind the backend named by --backend.
std::unique_ptr<wm::ModelBackend> load_backend(const Options& opts) {
  const std::string name = opts.get("backend");
  try {
    wm::check_model_backend_name(name);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--backend: ") + e.what());
  }
  try {
    return wm::make_model_backend(name, opts.get("URDF"), load_options(opts));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
}

json limit(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json rows(const Eigen::MatrixXd& m) {
  json out = json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    json row = json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) {
      row.push_back(m(r, c));
    }
    out.push_back(row);
  }
  return out;
}

json vec(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    out.push_back(v[i]);
  }
  return out;
}

std::string type_name(const wm::Model& m, int k) {
  if (m.joint_type[static_cast<std::size_t>(k)] == wm::JointType::kPrismatic) {
    return "prismatic";
  }
  return m.joint_continuous[static_cast<std::size_t>(k)] ? "continuous" : "revolute";
}

// ---------------------------------------------------------------- info

int run_info(Args args) {
  Options opts(
      "wbi model info URDF [--fixed-base] [--joints a,b,...] [--armature j=v,...] [--json]",
      "Print the model built from a URDF: base kind, joints in order with their limits\n"
      "and armature, bodies after lumping fixed joints, frames (every link) and the total "
      "mass.");
  opts.positional("URDF", "the robot description (.urdf)")
      .flag("fixed-base",
            "fix the root link to the world (default: free-floating, unless the root is a massless "
            "'world')")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated, in this order); lock the "
              "rest at 0")
      .option("armature", "LIST", kArmatureHelp)
      .flag("json", "print JSON instead of text");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  const wm::Model m = load(opts);
  json out;
  out["name"] = m.name;
  out["file"] = m.source;
  out["base"] = m.floating_base ? "floating" : "fixed";
  out["root_link"] = m.body_name[0];
  out["nq"] = m.nq;
  out["nv"] = m.nv;
  out["total_mass"] = m.total_mass;
  out["joints"] = json::array();
  for (int k = 0; k < m.n_joints; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    json j;
    j["name"] = m.joint_name[uk];
    j["type"] = type_name(m, k);
    j["body"] = m.body_name[static_cast<std::size_t>(m.joint_body[uk])];
    j["parent_body"] =
        m.body_name[static_cast<std::size_t>(m.parent[static_cast<std::size_t>(m.joint_body[uk])])];
    j["lower"] = limit(m.joint_lower[uk]);
    j["upper"] = limit(m.joint_upper[uk]);
    j["velocity"] = limit(m.joint_velocity_limit[uk]);
    j["effort"] = limit(m.joint_effort_limit[uk]);
    j["armature"] = m.joint_armature[uk];
    if (!m.joint_mimic[uk].joint.empty()) {
      j["mimic"] = {{"joint", m.joint_mimic[uk].joint},
                    {"multiplier", m.joint_mimic[uk].multiplier},
                    {"offset", m.joint_mimic[uk].offset},
                    {"policy", "independent joint"}};
    }
    out["joints"].push_back(j);
  }
  out["locked_joints"] = json::array();
  for (std::size_t k = 0; k < m.locked_joint_name.size(); ++k) {
    out["locked_joints"].push_back(
        {{"name", m.locked_joint_name[k]}, {"position", m.locked_joint_position[k]}});
  }
  out["bodies"] = json::array();
  for (int i = 0; i < m.n_bodies; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    json b;
    b["name"] = m.body_name[ui];
    b["parent"] =
        i == 0 ? json(nullptr) : json(m.body_name[static_cast<std::size_t>(m.parent[ui])]);
    b["mass"] = m.body_mass[ui];
    b["com"] = vec(m.body_com[ui]);
    json frames = json::array();
    for (int f = 0; f < m.n_frames(); ++f) {
      if (m.frame_body[static_cast<std::size_t>(f)] == i) {
        frames.push_back(m.frame_name[static_cast<std::size_t>(f)]);
      }
    }
    b["frames"] = frames;
    out["bodies"].push_back(b);
  }
  out["frames"] = json::array();
  for (int f = 0; f < m.n_frames(); ++f) {
    const auto uf = static_cast<std::size_t>(f);
    out["frames"].push_back({{"name", m.frame_name[uf]},
                             {"body", m.body_name[static_cast<std::size_t>(m.frame_body[uf])]},
                             {"position", vec(m.frame_p_BF[uf])}});
  }
  if (opts.has("json")) {
    std::cout << out.dump(2) << "\n";
    return kExitOk;
  }
  std::cout << "model:      " << m.name << " (" << m.source << ")\n"
            << "base:       " << (m.floating_base ? "floating" : "fixed") << " (root link '"
            << m.body_name[0] << "')\n"
            << "sizes:      nq = " << m.nq << ", nv = " << m.nv << ", " << m.n_joints << " joints, "
            << m.n_bodies << " bodies, " << m.n_frames() << " frames\n"
            << "total mass: " << m.total_mass << " kg\n\njoints (in the order of q and ν):\n";
  auto fmt = [](double x) {
    std::ostringstream s;
    if (std::isfinite(x)) {
      s << x;
    } else {
      s << (x > 0 ? "inf" : "-inf");
    }
    return s.str();
  };
  for (int k = 0; k < m.n_joints; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    std::cout << "  " << std::setw(3) << k << "  " << std::left << std::setw(28) << m.joint_name[uk]
              << std::setw(11) << type_name(m, k) << std::right << " [" << fmt(m.joint_lower[uk])
              << ", " << fmt(m.joint_upper[uk]) << "]  vel " << fmt(m.joint_velocity_limit[uk])
              << "  effort " << fmt(m.joint_effort_limit[uk]) << "  armature "
              << fmt(m.joint_armature[uk]);
    if (!m.joint_mimic[uk].joint.empty()) {
      std::cout << "  (mimics " << m.joint_mimic[uk].joint << ", treated as independent)";
    }
    std::cout << "\n";
  }
  if (!m.locked_joint_name.empty()) {
    std::cout << "\nlocked joints:\n";
    for (std::size_t k = 0; k < m.locked_joint_name.size(); ++k) {
      std::cout << "  " << m.locked_joint_name[k] << " = " << m.locked_joint_position[k] << "\n";
    }
  }
  std::cout << "\nbodies (after lumping fixed joints):\n";
  for (const auto& b : out["bodies"]) {
    std::cout << "  " << std::left << std::setw(28) << b["name"].get<std::string>() << std::right
              << " mass " << std::setw(10) << b["mass"].get<double>() << "  frames:";
    for (const auto& f : b["frames"]) {
      std::cout << " " << f.get<std::string>();
    }
    std::cout << "\n";
  }
  return kExitOk;
}

// ---------------------------------------------------------------- eval

json read_state(const std::string& where) {
  std::string text;
  if (where == "-") {
    std::ostringstream s;
    s << std::cin.rdbuf();
    text = s.str();
  } else {
    std::ifstream in(where);
    if (!in) {
      throw std::runtime_error("state file '" + where + "': cannot open");
    }
    std::ostringstream s;
    s << in.rdbuf();
    text = s.str();
  }
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

int run_eval(Args args) {
  Options opts(
      "wbi model eval URDF --state FILE|- [--fixed-base] [--joints a,b,...] [--armature j=v,...]",
      "Evaluate the model at a state read as JSON and print the results as JSON.\n"
      "State keys (all optional): q, dq (in the order of 'joints' when given, else the model's),\n"
      "base_position [3], base_quaternion [w,x,y,z], base_velocity [6: linear, angular, world "
      "axes],\n"
      "gravity [3] (default [0,0,-9.81]), frames [names], joints [every joint, in the caller's "
      "order].\n"
      "Output keys: backend, joints, mass_matrix, bias_forces, gravity_forces, total_mass, com,\n"
      "centroidal_momentum, frames {name: {transform 4x4, jacobian 6x(n+6), dJnu [6]}}.\n"
      "Sizes are n+6 for a free-floating model, n with a fixed base; matrices are arrays of rows.");
  opts.positional("URDF", "the robot description (.urdf)")
      .option("state", "FILE", "the state as JSON, '-' for standard input")
      .flag("fixed-base", "fix the root link to the world")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated, in this order); lock the "
              "rest at 0")
      .option("armature", "LIST", kArmatureHelp)
      .option("backend", "NAME", kBackendHelp, "wbi");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  const std::string state_file = opts.get("state");
  const auto backend = load_backend(opts);
  const wm::Model& m = backend->model();
  const json state = read_state(state_file);
  static const std::set<std::string> kKeys{
      "q",       "dq",     "base_position", "base_quaternion", "base_velocity",
      "gravity", "frames", "joints"};
  for (const auto& [key, value] : state.items()) {
    if (kKeys.count(key) == 0) {
      throw std::runtime_error("state: unknown key '" + key + "'");
    }
  }
  const auto n = static_cast<std::size_t>(m.n_joints);
  // order[k] = model joint index of the caller's k-th joint
  std::vector<int> order;
  std::vector<std::string> names;
  if (state.contains("joints")) {
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
      order.push_back(m.joint_id(name));
      names.push_back(name);
    }
    if (order.size() != n) {
      for (const auto& jn : m.joint_name) {
        if (seen.count(jn) == 0) {
          throw std::runtime_error("state: 'joints' must list every joint of the model; '" + jn +
                                   "' is missing");
        }
      }
    }
  } else {
    for (int k = 0; k < m.n_joints; ++k) {
      order.push_back(k);
      names.push_back(m.joint_name[static_cast<std::size_t>(k)]);
    }
  }
  const Eigen::VectorXd s =
      state.contains("q") ? numbers(state, "q", n) : Eigen::VectorXd::Zero(m.n_joints);
  const Eigen::VectorXd ds =
      state.contains("dq") ? numbers(state, "dq", n) : Eigen::VectorXd::Zero(m.n_joints);
  Eigen::Vector3d gravity(0.0, 0.0, -9.81);
  if (state.contains("gravity")) {
    gravity = numbers(state, "gravity", 3);
  }
  for (const char* key : {"base_position", "base_quaternion", "base_velocity"}) {
    if (!m.floating_base && state.contains(key)) {
      throw std::runtime_error(std::string("state: '") + key +
                               "' given, but the model has a fixed base");
    }
  }
  Eigen::VectorXd q = wm::neutral_configuration(m);
  Eigen::VectorXd nu = Eigen::VectorXd::Zero(m.nv);
  if (m.floating_base) {
    if (state.contains("base_position")) {
      q.head<3>() = numbers(state, "base_position", 3);
    }
    if (state.contains("base_quaternion")) {
      const Eigen::VectorXd quat = numbers(state, "base_quaternion", 4);
      if (std::abs(quat.norm() - 1.0) > 1e-6) {
        throw std::runtime_error("state: 'base_quaternion' [w,x,y,z] has norm " +
                                 std::to_string(quat.norm()) + ", expected a unit quaternion");
      }
      q.segment<4>(3) = quat;
    }
    if (state.contains("base_velocity")) {
      nu.head<6>() = numbers(state, "base_velocity", 6);
    }
  }
  // caller order → model order
  for (std::size_t k = 0; k < n; ++k) {
    const int mk = order[k];
    q[m.joint_q_index[static_cast<std::size_t>(mk)]] = s[static_cast<Eigen::Index>(k)];
    nu[m.joint_v_index[static_cast<std::size_t>(mk)]] = ds[static_cast<Eigen::Index>(k)];
  }
  // permutation of ν: caller index → model index
  std::vector<int> perm;
  for (int b = 0; b < m.base_nv; ++b) {
    perm.push_back(b);
  }
  for (std::size_t k = 0; k < n; ++k) {
    perm.push_back(m.joint_v_index[static_cast<std::size_t>(order[k])]);
  }
  const auto nv = static_cast<Eigen::Index>(perm.size());
  auto permute_cols = [&](const Eigen::MatrixXd& a) {
    Eigen::MatrixXd r(a.rows(), nv);
    for (Eigen::Index c = 0; c < nv; ++c) {
      r.col(c) = a.col(perm[static_cast<std::size_t>(c)]);
    }
    return r;
  };
  auto permute_vec = [&](const Eigen::VectorXd& a) {
    Eigen::VectorXd r(nv);
    for (Eigen::Index c = 0; c < nv; ++c) {
      r[c] = a[perm[static_cast<std::size_t>(c)]];
    }
    return r;
  };
  json out;
  try {
    const Eigen::MatrixXd M = permute_cols(backend->mass_matrix(q));
    Eigen::MatrixXd Mp(nv, nv);
    for (Eigen::Index r = 0; r < nv; ++r) {
      Mp.row(r) = M.row(perm[static_cast<std::size_t>(r)]);
    }
    out["joints"] = names;
    out["mass_matrix"] = rows(Mp);
    out["bias_forces"] = vec(permute_vec(backend->bias_forces(q, nu, gravity)));
    out["gravity_forces"] = vec(permute_vec(backend->gravity_forces(q, gravity)));
    out["total_mass"] = m.total_mass;
    out["com"] = m.total_mass > 0.0 ? vec(backend->center_of_mass(q)) : json(nullptr);
    out["centroidal_momentum"] =
        m.total_mass > 0.0 ? vec(backend->centroidal_momentum(q, nu)) : json(nullptr);
    out["backend"] = std::string(backend->name());
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
        json fr;
        fr["transform"] = rows(backend->frame_pose(q, id));
        fr["jacobian"] = rows(permute_cols(backend->frame_jacobian(q, id)));
        fr["dJnu"] = vec(backend->frame_bias_acceleration(q, nu, id));
        out["frames"][name] = fr;
      }
    }
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  std::cout << out.dump(2) << "\n";
  return kExitOk;
}

// ---------------------------------------------------------------- bench

// Median over batches of the mean ns per call in a batch of `batch` calls; call b of
// batch s is at state (s + b) mod states, so that consecutive calls never repeat a
// state (a backend that caches on unchanged inputs, like DART, is timed computing).
template <typename Call>
double median_ns(int states, int batch, Call call) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> samples;
  for (int s = 0; s < states; ++s) {
    const auto t0 = Clock::now();
    for (int b = 0; b < batch; ++b) {
      call((s + b) % states);
    }
    const auto t1 = Clock::now();
    samples.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / batch);
  }
  std::nth_element(samples.begin(),
                   samples.begin() + static_cast<std::ptrdiff_t>(samples.size() / 2),
                   samples.end());
  return samples[samples.size() / 2];
}

int run_bench(Args args) {
  Options opts(
      "wbi model bench URDF [--backend wbi|dart] [--fixed-base] [--armature j=v,...] [--json]",
      "Time the main operations of a model backend on a URDF: median ns per call over\n"
      "batches of calls cycling through random states. forward_kinematics_ns is the pose\n"
      "of the Jacobian frame from q (wbi: all bodies; dart: the frame's ancestors, lazily).\n"
      "Also see bench/model (Google Benchmark suite wbi_bench_model).");
  opts.positional("URDF", "the robot description (.urdf)")
      .flag("fixed-base", "fix the root link to the world")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated, in this order)")
      .option("armature", "LIST", kArmatureHelp)
      .option("states", "N", "number of random states", "101")
      .option("batch", "N", "calls per batch", "200")
      .option("backend", "NAME", kBackendHelp, "wbi")
      .flag("json", "print JSON instead of text");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  const long states = opts.get_int("states");
  const long batch = opts.get_int("batch");
  if (states < 1 || batch < 1) {
    throw UsageError("--states and --batch must be at least 1");
  }
  const auto backend = load_backend(opts);
  wm::ModelBackend& be = *backend;
  const wm::Model& m = backend->model();
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Eigen::VectorXd> q, nu, tau, dnu;
  for (long s = 0; s < states; ++s) {
    q.push_back(wm::random_configuration(m, rng));
    Eigen::VectorXd v(m.nv), t(m.nv), a(m.nv);
    for (int k = 0; k < m.nv; ++k) {
      v[k] = unit(rng);
      t[k] = unit(rng);
      a[k] = unit(rng);
    }
    nu.push_back(v);
    tau.push_back(t);
    dnu.push_back(a);
  }
  // the frame for the Jacobian: the first frame on a deepest body (a hand or a foot)
  int frame = 0;
  int deepest = -1;
  for (int f = 0; f < m.n_frames(); ++f) {
    int depth = 0;
    for (int i = m.frame_body[static_cast<std::size_t>(f)]; i > 0;
         i = m.parent[static_cast<std::size_t>(i)]) {
      ++depth;
    }
    if (depth > deepest) {
      deepest = depth;
      frame = f;
    }
  }
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  const int S = static_cast<int>(states);
  const int B = static_cast<int>(batch);
  auto at = [&](int s) { return static_cast<std::size_t>(s); };
  volatile double sink = 0.0;
  json out;
  out["model"] = m.name;
  out["file"] = m.source;
  out["backend"] = std::string(be.name());
  out["nv"] = m.nv;
  out["mass_matrix_ns"] =
      median_ns(S, B, [&](int s) { sink = sink + be.mass_matrix(q[at(s)])(0, 0); });
  out["bias_forces_ns"] =
      median_ns(S, B, [&](int s) { sink = sink + be.bias_forces(q[at(s)], nu[at(s)], g)[0]; });
  out["gravity_forces_ns"] =
      median_ns(S, B, [&](int s) { sink = sink + be.gravity_forces(q[at(s)], g)[0]; });
  out["inverse_dynamics_ns"] = median_ns(S, B, [&](int s) {
    sink = sink + be.inverse_dynamics(q[at(s)], nu[at(s)], dnu[at(s)], g)[0];
  });
  out["forward_dynamics_ns"] = median_ns(S, B, [&](int s) {
    sink = sink + be.forward_dynamics(q[at(s)], nu[at(s)], tau[at(s)], g)[0];
  });
  out["jacobian_ns"] =
      median_ns(S, B, [&](int s) { sink = sink + be.frame_jacobian(q[at(s)], frame)(0, 0); });
  out["forward_kinematics_ns"] =
      median_ns(S, B, [&](int s) { sink = sink + be.frame_pose(q[at(s)], frame)(0, 3); });
  out["centroidal_momentum_matrix_ns"] =
      median_ns(S, B, [&](int s) { sink = sink + be.centroidal_momentum_matrix(q[at(s)])(0, 0); });
  out["jacobian_frame"] = m.frame_name[static_cast<std::size_t>(frame)];
  if (opts.has("json")) {
    std::cout << out.dump(2) << "\n";
    return kExitOk;
  }
  std::cout << "model " << m.name << " (" << m.source << "), nv = " << m.nv << ", backend "
            << be.name() << ", median ns per call over " << states << " random states:\n";
  for (const char* key : {"mass_matrix_ns", "bias_forces_ns", "gravity_forces_ns",
                          "inverse_dynamics_ns", "forward_dynamics_ns", "jacobian_ns",
                          "forward_kinematics_ns", "centroidal_momentum_matrix_ns"}) {
    std::cout << "  " << std::left << std::setw(32) << key << std::right << std::setw(10)
              << std::fixed << std::setprecision(0) << out[key].get<double>() << "\n";
  }
  std::cout << "  (jacobian_ns: frame '" << out["jacobian_frame"].get<std::string>()
            << "', including the kinematics of its support)\n";
  return kExitOk;
}

// ---------------------------------------------------------------- mjcf

int run_mjcf(Args args) {
  Options opts(
      "wbi model mjcf URDF -o FILE|- [--robot-config FILE] [--fixed-base] [--joints a,b,...]\n"
      "               [--welded a,b,...] [--timestep S] [--integrator NAME]",
      "Write the model as MJCF (MuJoCo's XML) that MuJoCo loads as the same multibody as\n"
      "wbi's model library: the bodies after lumping fixed joints, joints with axes and\n"
      "limits, inertias written to the last bit, and a free joint on the root link's frame\n"
      "when the base floats. Non-physical link inertias (MuJoCo rejects them) are replaced\n"
      "by the nearest physical ones, as LoadOptions::repair_inertia does in wbi's model,\n"
      "and each such link is named on stderr. With --robot-config, what the MuJoCo engine\n"
      "loads for that robot config: its joints' armature, damping and friction, contact\n"
      "geometry and ground, IMU and F/T sites and sensors (F/T child links welded as\n"
      "bodies of their own), and its mujoco: timestep and integrator. See\n"
      "model_service/mjcf/README.md and robot_side/mujoco_sim/README.md.");
  opts.positional("URDF", "the robot description (.urdf)")
      .option("output", "FILE", "where to write the MJCF (also -o FILE); '-' for standard output")
      .option("robot-config", "FILE",
              "a robot config (deploy/robots/*.yaml) whose URDF is URDF: write what the MuJoCo "
              "engine loads")
      .flag("fixed-base", "fix the root link to the world")
      .option("joints", "LIST",
              "reduced model: keep only these joints (comma-separated); lock the rest at 0")
      .option("welded", "LIST",
              "links lumped by fixed joints to keep as MuJoCo bodies of their own, welded to "
              "their parent (comma-separated; e.g. the child links of F/T sensors)")
      .option("timestep", "SECONDS",
              "MuJoCo's integration step (default 0.001, or the robot config's)")
      .option("integrator", "NAME",
              "MuJoCo's integrator: euler, rk4 or implicit (default euler, or the robot "
              "config's)");
  if (!opts.parse(args)) {
    return kExitOk;
  }
  if (!opts.has("output")) {
    throw UsageError("missing -o FILE (-o - writes to standard output)");
  }
  wm::Model m;
  wbi::mjcf::MjcfOptions options;
  try {
    if (const auto config_file = opts.get_optional("robot-config")) {
      if (opts.has("joints")) {
        throw UsageError("--joints: a robot config describes the whole robot (no reduced model)");
      }
      wbi::robot_config::RobotConfig config = wbi::robot_config::load_robot_config(*config_file);
      namespace fs = std::filesystem;
      if (fs::weakly_canonical(opts.get("URDF")) != fs::weakly_canonical(config.urdf)) {
        throw UsageError("URDF '" + opts.get("URDF") + "' is not the robot config's (" +
                         config.urdf + ")");
      }
      config.fixed_base = config.fixed_base || opts.has("fixed-base");
      m = wbi::mujoco_sim::robot_model(config);
      options = wbi::mujoco_sim::robot_mjcf(config, m, *config_file).options;
    } else {
      wm::LoadOptions load = load_options(opts);
      load.repair_inertia = true;
      m = wm::load_urdf_file(opts.get("URDF"), load);
    }
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  if (const auto timestep = opts.get_optional("timestep")) {
    options.timestep = opts.get_double("timestep");
    if (!(options.timestep > 0.0)) {
      throw UsageError("--timestep must be > 0");
    }
  }
  if (const auto integrator = opts.get_optional("integrator")) {
    const auto parsed = enum_from_name_any_case<Integrator>(*integrator);
    if (!parsed) {
      throw UsageError("--integrator: unknown '" + *integrator + "' (euler, rk4 or implicit)");
    }
    options.integrator = *parsed;
  }
  if (const auto welded = opts.get_optional("welded")) {
    for (const std::string& link : split_list(*welded, "welded", "link")) {
      options.welded_links.push_back(link);
    }
  }
  std::string xml;
  try {
    xml = wbi::mjcf::write_mjcf(m, options);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  for (const std::string& link : m.repaired_inertia_links) {
    std::cerr << "wbi model mjcf: link '" << link
              << "': non-physical inertia replaced by the nearest physical one (the same as "
                 "wbi's model with LoadOptions::repair_inertia)\n";
  }
  const std::string output = opts.get("output");
  if (output == "-") {
    std::cout << xml;
    return kExitOk;
  }
  std::ofstream out(output, std::ios::binary);
  out << xml;
  out.close();
  if (!out) {
    throw std::runtime_error("cannot write '" + output + "'");
  }
  std::cout << "wrote " << output << ": " << m.name << ", " << m.n_joints << " joints, "
            << m.n_bodies + static_cast<int>(options.welded_links.size()) << " bodies, "
            << (m.floating_base ? "free-floating" : "fixed base") << ", total mass " << m.total_mass
            << " kg\n";
  return kExitOk;
}

}  // namespace

int run_model(Args args) {
  if (args.empty()) {
    throw UsageError("missing sub-verb: info, eval, bench or mjcf");
  }
  const std::string& sub = args[0];
  if (sub == "--help" || sub == "-h") {
    std::cout << "usage: " << kModelUsage << "\n\n" << kModelHelp;
    return kExitOk;
  }
  const Args rest = args.subspan(1);
  if (sub == "info") {
    return run_info(rest);
  }
  if (sub == "eval") {
    return run_eval(rest);
  }
  if (sub == "bench") {
    return run_bench(rest);
  }
  if (sub == "mjcf") {
    return run_mjcf(rest);
  }
  throw UsageError("unknown sub-verb '" + sub + "' (expected info, eval, bench or mjcf)");
}

}  // namespace wbi::cli
