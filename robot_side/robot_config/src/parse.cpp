// YAML → RobotConfig, checked against the URDF (README.md lists every key).
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>
#include <Eigen/Geometry>

#include "wbi/model/urdf.hpp"
#include "wbi/robot_config/robot_config.hpp"
#include "yaml_reader.hpp"

namespace wbi::robot_config {

namespace {

// The robot the names are checked against.
struct Urdf {
  model::Model model;
  urdf::ModelInterfaceSharedPtr tree;
};

// A "joints:" entry before resolution: only the values it gives.
struct JointOverride {
  std::optional<double> armature, damping, friction, kp, kd;
};

class Parser {
 public:
  Parser(const YAML::Node& root, const std::string& context) : r_(context), root_(root) {}

  RobotConfig parse() {
    r_.check_keys(
        root_, "",
        {"urdf", "fixed_base", "gravity", "initial_joint_positions", "initial_base_position",
         "initial_base_orientation", "place_on_ground", "ground", "contacts", "joints",
         "joint_torque_sensors", "imus", "force_torque", "pushes", "wbi", "mujoco"});
    load_urdf();
    r_.get_vec<3>(root_, "", "gravity", c_.gravity);
    initial_state();
    ground();
    contacts();
    const auto overrides = joints();
    joint_torque_sensors();
    imus();
    force_torque();
    pushes();
    wbi();
    mujoco();
    complete_from_urdf(c_);
    apply(overrides);
    return c_;
  }

 private:
  void load_urdf() {
    const YAML::Node node = root_["urdf"];
    if (!node) {
      r_.fail(root_, "urdf", "required (the robot's URDF file)");
    }
    const auto written = r_.as<std::string>(node, "urdf");
    std::filesystem::path path(written);
    if (path.is_relative()) {
      path = std::filesystem::path(r_.context()).parent_path() / path;
    }
    path = std::filesystem::absolute(path).lexically_normal();
    if (!std::filesystem::is_regular_file(path)) {
      // The expected path as written, and where it led when it was relative.
      std::string where = path.string() == written ? "" : path.string();
      if (written.find("shared/models") != std::string::npos) {
        where = "the real robots' URDFs are expected in ../shared/models beside the repository" +
                (where.empty() ? "" : ": " + where);
      }
      r_.fail(node, "urdf", written + " not found" + (where.empty() ? "" : " (" + where + ")"));
    }
    c_.urdf = path.string();
    r_.get(root_, "", "fixed_base", c_.fixed_base);
    try {
      model::LoadOptions options;
      options.fixed_base = c_.fixed_base;
      urdf_.model = model::load_urdf_file(c_.urdf, options);
    } catch (const std::exception& e) {
      r_.fail(node, "urdf", e.what());
    }
    urdf_.tree = urdf::parseURDFFile(c_.urdf);
    if (!urdf_.tree) {
      r_.fail(node, "urdf", c_.urdf + ": urdfdom could not parse the file");
    }
  }

  void check_joint(const YAML::Node& at, const std::string& key, const std::string& joint) const {
    if (!urdf_.model.has_joint(joint)) {
      r_.fail(at, key, "unknown joint '" + joint + "' (not a movable joint of " + c_.urdf + ")");
    }
  }

  void check_frame(const YAML::Node& at, const std::string& key, const std::string& frame) const {
    if (!urdf_.model.has_frame(frame)) {
      r_.fail(at, key, "unknown link or frame '" + frame + "' in " + c_.urdf);
    }
  }

  // A required string naming a link or frame.
  std::string frame_key(const YAML::Node& node, const std::string& path, const char* key) const {
    std::string name;
    if (!r_.get(node, path, key, name) || name.empty()) {
      r_.fail(node, YamlReader::join(path, key), "required");
    }
    check_frame(node[key], YamlReader::join(path, key), name);
    return name;
  }

  void initial_state() {
    if (const auto init = root_["initial_joint_positions"]) {
      if (!init.IsMap()) {
        r_.fail(init, "initial_joint_positions", "expected a map joint: position");
      }
      for (const auto& kv : init) {
        const auto name = r_.key_of(init, kv.first, "initial_joint_positions");
        const std::string key = "initial_joint_positions." + name;
        check_joint(kv.first, key, name);
        c_.initial_joint_positions[name] = r_.as<double>(kv.second, key);
      }
    }
    r_.get_vec<3>(root_, "", "initial_base_position", c_.initial_base_position);
    if (r_.get_vec<4>(root_, "", "initial_base_orientation", c_.initial_base_orientation) &&
        !(c_.initial_base_orientation.norm() > 0.0)) {
      r_.fail(root_["initial_base_orientation"], "initial_base_orientation",
              "must be a non-zero quaternion (w, x, y, z)");
    }
    r_.get(root_, "", "place_on_ground", c_.place_on_ground);
  }

  void ground() {
    if (const auto n = root_["ground"]) {
      r_.check_keys(n, "ground", {"height", "friction"});
      r_.get(n, "ground", "height", c_.ground.height);
      r_.get_positive(n, "ground", "friction", c_.ground.friction, true);
    }
  }

  void contacts() {
    const YAML::Node list = r_.list(root_, "", "contacts");
    for (std::size_t i = 0; list && i < list.size(); ++i) {
      const YAML::Node n = list[i];
      const std::string p = "contacts[" + std::to_string(i) + "]";
      r_.check_keys(n, p, {"link", "box", "sphere", "capsule", "position", "rpy", "friction"});
      ContactGeometry g;
      g.link = frame_key(n, p, "link");
      int shapes = 0;
      if (const auto b = n["box"]) {
        ++shapes;
        g.shape = wbi::ContactShape::box;
        r_.check_keys(b, p + ".box", {"size"});
        if (!r_.get_vec<3>(b, p + ".box", "size", g.size)) {
          r_.fail(b, p + ".box.size", "required");
        }
        if (!(g.size.minCoeff() > 0.0)) {
          r_.fail(b["size"], p + ".box.size", "must be > 0");
        }
      }
      if (const auto s = n["sphere"]) {
        ++shapes;
        g.shape = wbi::ContactShape::sphere;
        r_.check_keys(s, p + ".sphere", {"radius"});
        if (!r_.get_positive(s, p + ".sphere", "radius", g.radius, false)) {
          r_.fail(s, p + ".sphere.radius", "required");
        }
      }
      if (const auto s = n["capsule"]) {
        ++shapes;
        g.shape = wbi::ContactShape::capsule;
        r_.check_keys(s, p + ".capsule", {"radius", "length"});
        if (!r_.get_positive(s, p + ".capsule", "radius", g.radius, false) ||
            !r_.get_positive(s, p + ".capsule", "length", g.length, true)) {
          r_.fail(s, p + ".capsule", "'radius' and 'length' are required");
        }
      }
      if (shapes != 1) {
        r_.fail(n, p, "expected exactly one of box, sphere, capsule");
      }
      r_.get_vec<3>(n, p, "position", g.position);
      Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
      r_.get_vec<3>(n, p, "rpy", rpy);
      // URDF convention: fixed axes x, then y, then z.
      g.rotation = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                    Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                    Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                       .toRotationMatrix();
      r_.get_positive(n, p, "friction", g.friction, true);
      c_.contacts.push_back(g);
    }
  }

  JointOverride joint_values(const YAML::Node& n, const std::string& p) const {
    r_.check_keys(n, p, {"armature", "damping", "friction", "kp", "kd"});
    JointOverride o;
    auto read = [&](const char* key, std::optional<double>& out) {
      double v = 0.0;
      if (r_.get_positive(n, p, key, v, true)) {
        out = v;
      }
    };
    read("armature", o.armature);
    read("damping", o.damping);
    read("friction", o.friction);
    read("kp", o.kp);
    read("kd", o.kd);
    return o;
  }

  // "default" first, then the joints in file order.
  std::vector<std::pair<std::string, JointOverride>> joints() const {
    std::vector<std::pair<std::string, JointOverride>> out;
    const YAML::Node n = root_["joints"];
    if (!n) {
      return out;
    }
    if (!n.IsMap()) {
      r_.fail(n, "joints", "expected a map joint: {armature, damping, friction, kp, kd}");
    }
    if (const auto d = n["default"]) {
      out.emplace_back("", joint_values(d, "joints.default"));
    }
    for (const auto& kv : n) {
      const auto name = r_.key_of(n, kv.first, "joints");
      if (name == "default") {
        continue;
      }
      const std::string p = "joints." + name;
      check_joint(kv.first, p, name);
      out.emplace_back(name, joint_values(kv.second, p));
    }
    return out;
  }

  void apply(const std::vector<std::pair<std::string, JointOverride>>& overrides) {
    auto set = [](JointDynamics& j, const JointOverride& o) {
      j.armature = o.armature.value_or(j.armature);
      j.damping = o.damping.value_or(j.damping);
      j.friction = o.friction.value_or(j.friction);
      j.kp = o.kp.value_or(j.kp);
      j.kd = o.kd.value_or(j.kd);
    };
    for (const auto& [name, o] : overrides) {
      if (name.empty()) {
        for (auto& entry : c_.joints) {
          set(entry.second, o);
        }
      } else {
        set(c_.joints.at(name), o);
      }
    }
  }

  // joint_torque_sensors: all | none | [joint, ...]
  void joint_torque_sensors() {
    const char* key = "joint_torque_sensors";
    const YAML::Node n = root_[key];
    if (!n) {
      return;
    }
    JointTorqueSensors& sensors = c_.joint_torque_sensors;
    if (n.IsScalar()) {
      const std::string& v = n.Scalar();
      if (v != "all" && v != "none") {
        r_.fail(n, key, "expected all, none or a list of joints, got '" + v + "'");
      }
      sensors.which =
          v == "all" ? JointTorqueSensors::Which::kAll : JointTorqueSensors::Which::kNone;
      return;
    }
    if (!n.IsSequence()) {
      r_.fail(n, key, "expected all, none or a list of joints");
    }
    sensors.which = JointTorqueSensors::Which::kListed;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const std::string p = std::string(key) + "[" + std::to_string(i) + "]";
      const auto name = r_.as<std::string>(n[i], p);
      check_joint(n[i], p, name);
      if (sensors.has(name)) {
        r_.fail(n[i], p, "joint '" + name + "' given twice");
      }
      sensors.joints.push_back(name);
    }
  }

  void imus() {
    const YAML::Node list = r_.list(root_, "", "imus");
    for (std::size_t i = 0; list && i < list.size(); ++i) {
      const std::string p = "imus[" + std::to_string(i) + "]";
      r_.check_keys(list[i], p, {"name", "frame", "gyro_noise", "accel_noise"});
      ImuConfig x;
      if (!r_.get(list[i], p, "name", x.name) || x.name.empty()) {
        r_.fail(list[i], p + ".name", "required");
      }
      x.frame = frame_key(list[i], p, "frame");
      r_.get_positive(list[i], p, "gyro_noise", x.gyro_noise, true);
      r_.get_positive(list[i], p, "accel_noise", x.accel_noise, true);
      c_.imus.push_back(x);
    }
  }

  void force_torque() {
    const YAML::Node list = r_.list(root_, "", "force_torque");
    for (std::size_t i = 0; list && i < list.size(); ++i) {
      const std::string p = "force_torque[" + std::to_string(i) + "]";
      r_.check_keys(list[i], p, {"name", "joint", "force_noise", "torque_noise"});
      ForceTorqueConfig x;
      if (!r_.get(list[i], p, "joint", x.joint) || x.joint.empty()) {
        r_.fail(list[i], p + ".joint", "required (a fixed joint of the URDF)");
      }
      const auto joint = urdf_.tree->getJoint(x.joint);
      if (!joint) {
        r_.fail(list[i]["joint"], p + ".joint", "unknown joint '" + x.joint + "' in " + c_.urdf);
      }
      if (joint->type != urdf::Joint::FIXED) {
        r_.fail(list[i]["joint"], p + ".joint", "'" + x.joint + "' is not a fixed joint");
      }
      r_.get(list[i], p, "name", x.name);
      if (x.name.empty()) {
        x.name = x.joint;
      }
      r_.get_positive(list[i], p, "force_noise", x.force_noise, true);
      r_.get_positive(list[i], p, "torque_noise", x.torque_noise, true);
      c_.force_torque.push_back(x);
    }
  }

  void pushes() {
    const YAML::Node list = r_.list(root_, "", "pushes");
    for (std::size_t i = 0; list && i < list.size(); ++i) {
      const std::string p = "pushes[" + std::to_string(i) + "]";
      r_.check_keys(list[i], p, {"link", "start", "duration", "force", "point"});
      PushConfig x;
      x.link = frame_key(list[i], p, "link");
      r_.get_positive(list[i], p, "start", x.start, true);
      r_.get_positive(list[i], p, "duration", x.duration, true);
      r_.get_vec<3>(list[i], p, "force", x.force);
      r_.get_vec<3>(list[i], p, "point", x.point);
      c_.pushes.push_back(x);
    }
  }

  void wbi() {
    const YAML::Node n = root_["wbi"];
    if (!n) {
      return;
    }
    WbiOptions& w = c_.wbi;
    r_.check_keys(n, "wbi",
                  {"step", "substeps", "friction_velocity", "joint_limits", "contact", "encoders",
                   "motor", "seed"});
    r_.get_positive(n, "wbi", "step", w.step, false);
    if (r_.get(n, "wbi", "substeps", w.substeps) && w.substeps < 1) {
      r_.fail(n["substeps"], "wbi.substeps", "must be >= 1");
    }
    r_.get_positive(n, "wbi", "friction_velocity", w.friction_velocity, false);
    if (const auto l = n["joint_limits"]) {
      r_.check_keys(l, "wbi.joint_limits", {"stiffness", "damping"});
      r_.get(l, "wbi.joint_limits", "stiffness", w.joint_limits.stiffness);
      r_.get(l, "wbi.joint_limits", "damping", w.joint_limits.damping);
    }
    if (const auto k = n["contact"]) {
      const std::string p = "wbi.contact";
      ContactModel& m = w.contact;
      r_.check_keys(k, p,
                    {"enable", "stiffness", "damping", "tangential", "tangential_stiffness",
                     "tangential_damping", "slip_velocity"});
      r_.get_enum<ContactModel::Enable>(k, p, "enable",
                                        {{"auto", ContactModel::Enable::kAuto},
                                         {"true", ContactModel::Enable::kOn},
                                         {"false", ContactModel::Enable::kOff}},
                                        m.enable);
      r_.get_positive(k, p, "stiffness", m.stiffness, false);
      r_.get_positive(k, p, "damping", m.damping, true);
      r_.get_enum<ContactModel::Tangential>(
          k, p, "tangential",
          {{"spring", ContactModel::Tangential::kSpring},
           {"regularized", ContactModel::Tangential::kRegularized}},
          m.tangential);
      r_.get_positive(k, p, "tangential_stiffness", m.tangential_stiffness, false);
      r_.get_positive(k, p, "tangential_damping", m.tangential_damping, true);
      r_.get_positive(k, p, "slip_velocity", m.slip_velocity, false);
    }
    if (const auto e = n["encoders"]) {
      const std::string p = "wbi.encoders";
      r_.check_keys(e, p,
                    {"counts_per_revolution", "position_noise", "velocity_noise", "torque_noise"});
      r_.get_positive(e, p, "counts_per_revolution", w.encoders.counts_per_revolution, true);
      r_.get_positive(e, p, "position_noise", w.encoders.position_noise, true);
      r_.get_positive(e, p, "velocity_noise", w.encoders.velocity_noise, true);
      r_.get_positive(e, p, "torque_noise", w.encoders.torque_noise, true);
    }
    if (const auto m = n["motor"]) {
      const std::string p = "wbi.motor";
      r_.check_keys(m, p, {"voltage", "resistance", "torque_constant", "back_emf"});
      r_.get_positive(m, p, "voltage", w.motor.voltage, false);
      r_.get_positive(m, p, "resistance", w.motor.resistance, false);
      r_.get_positive(m, p, "torque_constant", w.motor.torque_constant, true);
      r_.get_positive(m, p, "back_emf", w.motor.back_emf, true);
    }
    r_.get(n, "wbi", "seed", w.seed);
  }

  void mujoco() {
    const YAML::Node n = root_["mujoco"];
    if (!n) {
      return;
    }
    const std::string p = "mujoco";
    MujocoOptions& m = c_.mujoco;
    r_.check_keys(n, p,
                  {"timestep", "substeps", "integrator", "solref", "solimp", "cone", "impratio",
                   "joint_friction"});
    r_.get_positive(n, p, "timestep", m.timestep, false);
    if (r_.get(n, p, "substeps", m.substeps) && m.substeps < 1) {
      r_.fail(n["substeps"], "mujoco.substeps", "must be >= 1");
    }
    r_.get_enum<Integrator>(n, p, "integrator",
                            {{to_string(Integrator::euler), Integrator::euler},
                             {to_string(Integrator::implicit), Integrator::implicit},
                             {to_string(Integrator::rk4), Integrator::rk4}},
                            m.integrator);
    Eigen::Vector2d solref(m.solref[0], m.solref[1]);
    if (r_.get_vec<2>(n, p, "solref", solref)) {
      // (timeconst, dampratio) both > 0, or the direct form (−stiffness, −damping).
      if (!((solref[0] > 0.0 && solref[1] > 0.0) || (solref[0] < 0.0 && solref[1] <= 0.0))) {
        r_.fail(n["solref"], "mujoco.solref",
                "expected [timeconst > 0, dampratio > 0] or [-stiffness < 0, -damping <= 0]");
      }
      m.solref = {solref[0], solref[1]};
    }
    Eigen::Matrix<double, 5, 1> solimp;
    solimp << m.solimp[0], m.solimp[1], m.solimp[2], m.solimp[3], m.solimp[4];
    if (r_.get_vec<5>(n, p, "solimp", solimp)) {
      auto open01 = [](double x) { return x > 0.0 && x < 1.0; };
      if (!open01(solimp[0]) || !open01(solimp[1]) || !(solimp[2] >= 0.0) || !open01(solimp[3]) ||
          !(solimp[4] >= 1.0)) {
        r_.fail(n["solimp"], "mujoco.solimp",
                "expected [dmin, dmax in (0, 1), width >= 0, midpoint in (0, 1), power >= 1]");
      }
      m.solimp = {solimp[0], solimp[1], solimp[2], solimp[3], solimp[4]};
    }
    r_.get_enum<MujocoOptions::Cone>(n, p, "cone",
                                     {{"pyramidal", MujocoOptions::Cone::kPyramidal},
                                      {"elliptic", MujocoOptions::Cone::kElliptic}},
                                     m.cone);
    r_.get_positive(n, p, "impratio", m.impratio, false);
    r_.get_enum<MujocoOptions::JointFriction>(
        n, p, "joint_friction",
        {{"torque", MujocoOptions::JointFriction::kTorque},
         {"constraint", MujocoOptions::JointFriction::kConstraint}},
        m.joint_friction);
  }

  YamlReader r_;
  YAML::Node root_;
  Urdf urdf_;
  RobotConfig c_;
};

}  // namespace

RobotConfig parse_robot_config(std::string_view yaml_text, const std::string& context) {
  YAML::Node root;
  try {
    root = YAML::Load(std::string(yaml_text));
  } catch (const YAML::Exception& e) {
    throw std::invalid_argument(context + ":" + std::to_string(e.mark.line + 1) +
                                ": yaml: " + e.msg);
  }
  if (!root.IsDefined() || root.IsNull()) {
    throw std::invalid_argument(context + ": <root>: empty document (expected at least 'urdf')");
  }
  try {
    return Parser(root, context).parse();
  } catch (const YAML::Exception& e) {  // a shape the checks above did not foresee
    throw std::invalid_argument(context + ":" + std::to_string(e.mark.line + 1) +
                                ": yaml: " + e.msg);
  }
}

RobotConfig load_robot_config(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    throw std::invalid_argument(path + ": cannot open the robot config file");
  }
  std::stringstream text;
  text << in.rdbuf();
  return parse_robot_config(text.str(), path);
}

}  // namespace wbi::robot_config
