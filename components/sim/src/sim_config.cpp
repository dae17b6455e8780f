// YAML → SimConfig, with errors that name the key (README.md lists every key).
#include "wbi/sim/sim_config.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <stdexcept>

#include <yaml-cpp/yaml.h>

namespace wbi::sim {

namespace {

class Reader {
 public:
  explicit Reader(std::string context) : context_(std::move(context)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw std::invalid_argument(context_ + ": '" + key + "': " + what);
  }

  void check_keys(const YAML::Node& node, const std::string& path,
                  std::initializer_list<const char*> allowed) const {
    if (!node.IsMap()) {
      fail(path.empty() ? "<root>" : path, "expected a map");
    }
    for (const auto& kv : node) {
      const auto key = kv.first.as<std::string>();
      bool ok = false;
      std::string list;
      for (const char* a : allowed) {
        ok = ok || key == a;
        list += list.empty() ? a : std::string(", ") + a;
      }
      if (!ok) {
        fail(join(path, key), "unknown key (allowed: " + list + ")");
      }
    }
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  template <typename T>
  void get(const YAML::Node& node, const std::string& path, const char* key, T& out) const {
    const YAML::Node v = node[key];
    if (!v) {
      return;
    }
    try {
      out = v.as<T>();
    } catch (const YAML::Exception&) {
      fail(join(path, key), "wrong type");
    }
  }

  void get_positive(const YAML::Node& node, const std::string& path, const char* key, double& out,
                    bool allow_zero) const {
    get(node, path, key, out);
    if (!(out > 0.0 || (allow_zero && out >= 0.0))) {
      fail(join(path, key), allow_zero ? "must be >= 0" : "must be > 0");
    }
  }

  template <int N>
  void get_vec(const YAML::Node& node, const std::string& path, const char* key,
               Eigen::Matrix<double, N, 1>& out) const {
    const YAML::Node v = node[key];
    if (!v) {
      return;
    }
    if (!v.IsSequence() || v.size() != static_cast<std::size_t>(N)) {
      fail(join(path, key), "expected a list of " + std::to_string(N) + " numbers");
    }
    for (int i = 0; i < N; ++i) {
      try {
        out[i] = v[static_cast<std::size_t>(i)].as<double>();
      } catch (const YAML::Exception&) {
        fail(join(path, key), "expected numbers");
      }
    }
  }

  YAML::Node seq(const YAML::Node& node, const char* key) const {
    const YAML::Node v = node[key];
    if (v && !v.IsSequence()) {
      fail(key, "expected a list");
    }
    return v;
  }

 private:
  std::string context_;
};

}  // namespace

SimConfig sim_config_from_yaml(const YAML::Node& root, const std::string& context) {
  const Reader r(context);
  SimConfig c;
  r.check_keys(root, "",
               {"urdf",
                "fixed_base",
                "step",
                "substeps",
                "gravity",
                "initial_joint_positions",
                "initial_base_position",
                "initial_base_orientation",
                "place_on_ground",
                "armature",
                "joint_damping",
                "joint_friction",
                "friction_velocity",
                "joint_limits",
                "contact",
                "encoders",
                "motor",
                "imus",
                "force_torque",
                "pushes",
                "seed"});
  r.get(root, "", "urdf", c.urdf);
  r.get(root, "", "fixed_base", c.fixed_base);
  r.get_positive(root, "", "step", c.step, false);
  r.get(root, "", "substeps", c.substeps);
  if (c.substeps < 1) {
    r.fail("substeps", "must be >= 1");
  }
  r.get_vec<3>(root, "", "gravity", c.gravity);
  if (const auto init = root["initial_joint_positions"]) {
    if (!init.IsMap()) {
      r.fail("initial_joint_positions", "expected a map joint: position");
    }
    for (const auto& kv : init) {
      const auto name = kv.first.as<std::string>();
      try {
        c.initial_joint_positions[name] = kv.second.as<double>();
      } catch (const YAML::Exception&) {
        r.fail("initial_joint_positions." + name, "expected a number");
      }
    }
  }
  r.get_vec<3>(root, "", "initial_base_position", c.initial_base_position);
  r.get_vec<4>(root, "", "initial_base_orientation", c.initial_base_orientation);
  r.get(root, "", "place_on_ground", c.place_on_ground);
  if (const auto armature = root["armature"]) {
    if (!armature.IsMap()) {
      r.fail("armature", "expected a map joint: armature");
    }
    for (const auto& kv : armature) {
      const auto name = kv.first.as<std::string>();
      double value = 0.0;
      try {
        value = kv.second.as<double>();
      } catch (const YAML::Exception&) {
        r.fail("armature." + name, "expected a number");
      }
      if (!std::isfinite(value) || value < 0.0) {
        r.fail("armature." + name, "must be finite and >= 0");
      }
      c.armature[name] = value;
    }
  }
  r.get(root, "", "joint_damping", c.joint_damping);
  r.get(root, "", "joint_friction", c.joint_friction);
  r.get_positive(root, "", "friction_velocity", c.friction_velocity, false);
  if (const auto n = root["joint_limits"]) {
    r.check_keys(n, "joint_limits", {"stiffness", "damping"});
    r.get(n, "joint_limits", "stiffness", c.joint_limits.stiffness);
    r.get(n, "joint_limits", "damping", c.joint_limits.damping);
  }
  if (const auto n = root["contact"]) {
    const std::string p = "contact";
    r.check_keys(
        n, p,
        {"enable", "stiffness", "damping", "friction", "tangential", "tangential_stiffness",
         "tangential_damping", "slip_velocity", "links", "points"});
    if (const auto e = n["enable"]) {
      const auto v = e.as<std::string>();
      if (v == "auto") {
        c.contact.enable = ContactConfig::Enable::kAuto;
      } else if (v == "true" || v == "on") {
        c.contact.enable = ContactConfig::Enable::kOn;
      } else if (v == "false" || v == "off") {
        c.contact.enable = ContactConfig::Enable::kOff;
      } else {
        r.fail("contact.enable", "expected auto, true or false, got '" + v + "'");
      }
    }
    r.get_positive(n, p, "stiffness", c.contact.stiffness, false);
    r.get_positive(n, p, "damping", c.contact.damping, true);
    r.get_positive(n, p, "friction", c.contact.friction, true);
    if (const auto t = n["tangential"]) {
      const auto v = t.as<std::string>();
      if (v == "spring") {
        c.contact.tangential = ContactConfig::Tangential::kSpring;
      } else if (v == "regularized") {
        c.contact.tangential = ContactConfig::Tangential::kRegularized;
      } else {
        r.fail("contact.tangential", "expected spring or regularized, got '" + v + "'");
      }
    }
    r.get_positive(n, p, "tangential_stiffness", c.contact.tangential_stiffness, false);
    r.get_positive(n, p, "tangential_damping", c.contact.tangential_damping, true);
    r.get_positive(n, p, "slip_velocity", c.contact.slip_velocity, false);
    r.get(n, p, "links", c.contact.links);
    if (const auto pts = n["points"]) {
      if (!pts.IsSequence()) {
        r.fail("contact.points", "expected a list");
      }
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const std::string pp = "contact.points[" + std::to_string(i) + "]";
        r.check_keys(pts[i], pp, {"link", "position"});
        ContactPointConfig pc;
        r.get(pts[i], pp, "link", pc.link);
        if (pc.link.empty()) {
          r.fail(pp + ".link", "required");
        }
        r.get_vec<3>(pts[i], pp, "position", pc.position);
        c.contact.points.push_back(pc);
      }
    }
  }
  if (const auto n = root["encoders"]) {
    const std::string p = "encoders";
    r.check_keys(n, p,
                 {"counts_per_revolution", "position_noise", "velocity_noise", "torque_noise"});
    r.get_positive(n, p, "counts_per_revolution", c.encoders.counts_per_revolution, true);
    r.get_positive(n, p, "position_noise", c.encoders.position_noise, true);
    r.get_positive(n, p, "velocity_noise", c.encoders.velocity_noise, true);
    r.get_positive(n, p, "torque_noise", c.encoders.torque_noise, true);
  }
  if (const auto n = root["motor"]) {
    const std::string p = "motor";
    r.check_keys(n, p, {"voltage", "resistance", "torque_constant", "back_emf"});
    r.get_positive(n, p, "voltage", c.motor.voltage, false);
    r.get_positive(n, p, "resistance", c.motor.resistance, false);
    r.get_positive(n, p, "torque_constant", c.motor.torque_constant, true);
    r.get_positive(n, p, "back_emf", c.motor.back_emf, true);
  }
  if (const auto list = r.seq(root, "imus")) {
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string p = "imus[" + std::to_string(i) + "]";
      r.check_keys(list[i], p, {"name", "frame", "gyro_noise", "accel_noise"});
      ImuConfig x;
      r.get(list[i], p, "name", x.name);
      r.get(list[i], p, "frame", x.frame);
      if (x.name.empty() || x.frame.empty()) {
        r.fail(p, "'name' and 'frame' are required");
      }
      r.get_positive(list[i], p, "gyro_noise", x.gyro_noise, true);
      r.get_positive(list[i], p, "accel_noise", x.accel_noise, true);
      c.imus.push_back(x);
    }
  }
  if (const auto list = r.seq(root, "force_torque")) {
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string p = "force_torque[" + std::to_string(i) + "]";
      r.check_keys(list[i], p, {"name", "joint", "force_noise", "torque_noise"});
      ForceTorqueConfig x;
      r.get(list[i], p, "name", x.name);
      r.get(list[i], p, "joint", x.joint);
      if (x.joint.empty()) {
        r.fail(p, "'joint' is required");
      }
      if (x.name.empty()) {
        x.name = x.joint;
      }
      r.get_positive(list[i], p, "force_noise", x.force_noise, true);
      r.get_positive(list[i], p, "torque_noise", x.torque_noise, true);
      c.force_torque.push_back(x);
    }
  }
  if (const auto list = r.seq(root, "pushes")) {
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string p = "pushes[" + std::to_string(i) + "]";
      r.check_keys(list[i], p, {"link", "start", "duration", "force", "point"});
      PushConfig x;
      r.get(list[i], p, "link", x.link);
      if (x.link.empty()) {
        r.fail(p, "'link' is required");
      }
      r.get_positive(list[i], p, "start", x.start, true);
      r.get_positive(list[i], p, "duration", x.duration, true);
      r.get_vec<3>(list[i], p, "force", x.force);
      r.get_vec<3>(list[i], p, "point", x.point);
      c.pushes.push_back(x);
    }
  }
  r.get(root, "", "seed", c.seed);
  return c;
}

SimConfig parse_sim_config(std::string_view yaml_text, const std::string& context) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(context + ": YAML error at line " +
                                std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  return sim_config_from_yaml(root, context);
}

SimConfig load_sim_config_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument(path + ": cannot open the sim config file");
  }
  std::stringstream text;
  text << in.rdbuf();
  SimConfig c = parse_sim_config(text.str(), path);
  // A relative URDF path is relative to the config file.
  if (!c.urdf.empty() && std::filesystem::path(c.urdf).is_relative()) {
    c.urdf = (std::filesystem::path(path).parent_path() / c.urdf).lexically_normal().string();
  }
  return c;
}

}  // namespace wbi::sim
