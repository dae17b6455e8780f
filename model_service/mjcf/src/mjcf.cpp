// Model → MJCF text. One <body> per body of the model, nested as the tree, in
// the model's body order (MuJoCo's dof order is then the model's body order).
#include "wbi/mjcf/mjcf.hpp"

#include <charconv>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

namespace wbi::mjcf {

namespace {

namespace wm = wbi::model;
using Eigen::Matrix3d;
using Eigen::Vector3d;

// MuJoCo's mjMINVAL: moving bodies need a mass and principal moments at least this.
constexpr double kMuJoCoMinVal = 1e-15;

// The shortest text that reads back as exactly x (at most 17 significant digits).
std::string num(double x) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), x);
  return std::string(buffer, result.ptr);
}

std::string nums(std::initializer_list<double> xs) {
  std::string out;
  for (const double x : xs) {
    if (!out.empty()) {
      out += ' ';
    }
    out += num(x);
  }
  return out;
}

std::string vec3(const Vector3d& v) { return nums({v.x(), v.y(), v.z()}); }

// w x y z of a rotation matrix (made proper by the caller).
std::string quat(const Matrix3d& R) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(R).normalized();
  return nums({q.w(), q.x(), q.y(), q.z()});
}

std::string escape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string attr(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + escape(value) + "\"";
}

[[noreturn]] void fail(const std::string& what) { throw std::invalid_argument("MJCF: " + what); }

// Principal moments (ascending) and axes (a proper rotation) of a rotational inertia.
struct Principal {
  Vector3d moments;
  Matrix3d axes;
};

Principal principal(const Matrix3d& I) {
  const Eigen::SelfAdjointEigenSolver<Matrix3d> eig(I);
  Principal p{eig.eigenvalues(), eig.eigenvectors()};
  if (p.axes.determinant() < 0.0) {
    p.axes.col(2) = -p.axes.col(2);
  }
  return p;
}

// MuJoCo's own checks of a body's inertia (user_body: "mass and inertia cannot be
// negative", "inertia must satisfy A + B >= C"; user_model: "mass and inertia of
// moving bodies must be larger than mjMINVAL"), on the numbers as written.
void check_body_inertia(const std::string& body, bool moving, double mass, const Vector3d& d) {
  std::ostringstream moments;
  moments.precision(17);
  moments << d.x() << ", " << d.y() << ", " << d.z();
  if (mass < 0.0 || d.minCoeff() < 0.0 || d.x() + d.y() < d.z() || d.x() + d.z() < d.y() ||
      d.y() + d.z() < d.x()) {
    fail("body '" + body + "': principal moments of inertia (" + moments.str() +
         ") break the triangle inequality A + B >= C, which MuJoCo rejects; load the model "
         "with LoadOptions::repair_inertia (wbi model mjcf does)");
  }
  if (moving && (mass < kMuJoCoMinVal || d.minCoeff() < kMuJoCoMinVal)) {
    fail("body '" + body + "' moves but has mass " + num(mass) + " and principal moments (" +
         moments.str() + "); MuJoCo needs every moving body's mass and moments >= 1e-15");
  }
}

void check_vector(const std::vector<double>& v, const wm::Model& model, const char* what) {
  if (!v.empty() && v.size() != static_cast<std::size_t>(model.n_joints)) {
    fail(std::string(what) + ": " + std::to_string(v.size()) + " values for " +
         std::to_string(model.n_joints) + " joints (one per joint, in the model's order)");
  }
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!std::isfinite(v[k]) || v[k] < 0.0) {
      fail(std::string(what) + " of joint '" + model.joint_name[k] + "' is " + num(v[k]) +
           ", expected a finite value >= 0");
    }
  }
}

double value_or_zero(const std::vector<double>& v, int k) {
  return v.empty() ? 0.0 : v[static_cast<std::size_t>(k)];
}

struct Pose {
  Vector3d p = Vector3d::Zero();
  Matrix3d R = Matrix3d::Identity();
};

// a⁻¹ b: the pose b (given in the same frame as a) seen from a
Pose relative(const Pose& a, const Pose& b) {
  return {a.R.transpose() * (b.p - a.p), a.R.transpose() * b.R};
}

// An MJCF <body> is a "group" of frames of one model body, named by its head
// frame: the body's first link (the one its joint moves), or a welded link
// (MjcfOptions::welded_links), which takes the links lumped below it.
class Writer {
 public:
  Writer(const wm::Model& model, const MjcfOptions& options)
      : model_(model),
        options_(options),
        body_head_(static_cast<std::size_t>(model.n_bodies), -1),
        split_(static_cast<std::size_t>(model.n_bodies), false),
        group_(static_cast<std::size_t>(model.n_frames()), -1),
        children_(static_cast<std::size_t>(model.n_frames())) {
    floating_ = options.floating_base.value_or(model.floating_base);
    if (model.frame_parent.size() != static_cast<std::size_t>(model.n_frames()) ||
        model.frame_inertia.size() != static_cast<std::size_t>(model.n_frames())) {
      fail("the model has no frame_parent/frame_inertia (build it with wbi::model's loader)");
    }
    for (int f = 0; f < model.n_frames(); ++f) {
      const int b = model.frame_body[uz(f)];
      const int parent = model.frame_parent[uz(f)];
      if (parent < 0 || model.frame_body[uz(parent)] != b) {
        body_head_[uz(b)] = f;
      }
    }
    std::vector<bool> welded(uz(model.n_frames()), false);
    for (const std::string& link : options.welded_links) {
      if (!model.has_frame(link)) {
        fail("welded_links: unknown link '" + link + "'");
      }
      const int f = model.frame_id(link);
      if (body_head_[uz(model.frame_body[uz(f)])] == f) {
        fail("welded_links: link '" + link +
             "' is already a body of its own (a joint moves it, "
             "or it is the root)");
      }
      if (welded[uz(f)]) {
        fail("welded_links: link '" + link + "' is listed twice");
      }
      welded[uz(f)] = true;
      split_[uz(model.frame_body[uz(f)])] = true;
    }
    // frames come parent first (depth-first), so a parent's group is known
    for (int f = 0; f < model.n_frames(); ++f) {
      const bool head = body_head_[uz(model.frame_body[uz(f)])] == f || welded[uz(f)];
      group_[uz(f)] = head ? f : group_[uz(model.frame_parent[uz(f)])];
      if (head && model.frame_parent[uz(f)] >= 0) {
        children_[uz(group_[uz(model.frame_parent[uz(f)])])].push_back(f);
      }
    }
    check_options();
  }

  std::string write() {
    out_ << "<mujoco" << attr("model", model_.name) << ">\n"
         << "  <!-- written by wbi (wbi::mjcf::write_mjcf) from " << escape(model_.source)
         << "; fixed joints lumped as the model library lumps them -->\n"
         << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
         << "  <option" << attr("gravity", vec3(options_.gravity))
         << attr("timestep", num(options_.timestep))
         << attr("integrator", to_string(options_.integrator)) << "/>\n"
         << "  <size" << attr("njmax", std::to_string(options_.njmax))
         << attr("nconmax", std::to_string(options_.nconmax)) << "/>\n"
         << "  <worldbody>\n";
    if (options_.ground.enabled) {
      // contype 0, conaffinity 1 against the robot's contype 1, conaffinity 0:
      // robot-ground contacts only, never robot-robot.
      out_ << "    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\""
           << attr("pos", nums({0.0, 0.0, options_.ground.height}))
           << attr("friction", nums({options_.ground.friction, 0.005, 0.0001}))
           << " contype=\"0\" conaffinity=\"1\" condim=\"3\"/>\n";
    }
    write_group(body_head_[0], 2);
    out_ << "  </worldbody>\n";
    write_sensors();
    out_ << "</mujoco>\n";
    return out_.str();
  }

 private:
  static std::size_t uz(int i) { return static_cast<std::size_t>(i); }

  void check_options() const {
    if (!(options_.timestep > 0.0) || !std::isfinite(options_.timestep)) {
      fail("timestep must be > 0, got " + num(options_.timestep));
    }
    if (!options_.gravity.allFinite()) {
      fail("gravity must be finite");
    }
    if (options_.njmax < 0 || options_.nconmax < 0) {
      fail("njmax and nconmax must be >= 0");
    }
    check_vector(options_.armature, model_, "armature");
    check_vector(options_.damping, model_, "damping");
    check_vector(options_.frictionloss, model_, "frictionloss");
    if (floating_ && model_.has_joint(options_.free_joint_name)) {
      fail("free_joint_name '" + options_.free_joint_name + "' is a joint of the model");
    }
    std::set<std::string> geoms{"ground"};
    for (std::size_t c = 0; c < options_.contacts.size(); ++c) {
      const ContactGeometry& g = options_.contacts[c];
      const std::string what = "contact " + std::to_string(c) + " ('" + geom_name(c) + "')";
      if (!model_.has_frame(g.link)) {
        fail(what + ": unknown link '" + g.link + "'");
      }
      if (!geoms.insert(geom_name(c)).second) {
        fail(what + ": geom name used twice");
      }
      const bool ok = g.shape == ContactShape::box      ? (g.size.array() > 0.0).all()
                      : g.shape == ContactShape::sphere ? g.radius > 0.0
                                                        : g.radius > 0.0 && g.length > 0.0;
      if (!ok || !g.size.allFinite() || !std::isfinite(g.radius) || !std::isfinite(g.length)) {
        fail(what +
             ": a box needs size > 0 in x, y, z; a sphere radius > 0; a capsule radius "
             "and length > 0");
      }
      if (!(g.friction >= 0.0) || !std::isfinite(g.friction)) {
        fail(what + ": friction must be finite and >= 0");
      }
    }
    std::set<std::string> sites;
    for (const Site& s : options_.sites) {
      if (s.name.empty() || !sites.insert(s.name).second) {
        fail("site '" + s.name + "': empty or used twice");
      }
      if (!model_.has_frame(s.frame)) {
        fail("site '" + s.name + "': unknown frame '" + s.frame + "'");
      }
    }
  }

  std::string geom_name(std::size_t c) const {
    const ContactGeometry& g = options_.contacts[c];
    return g.name.empty() ? g.link + "_contact_" + std::to_string(c) : g.name;
  }

  Pose frame_pose(int f) const { return {model_.frame_p_BF[uz(f)], model_.frame_R_BF[uz(f)]}; }

  // Something given in frame f's coordinates, seen from the head of f's group.
  Pose in_group(int f, const Vector3d& p, const Matrix3d& R) const {
    const Pose X_BF = frame_pose(f);
    const Pose X_BX{X_BF.p + X_BF.R * p, X_BF.R * R};
    return relative(frame_pose(group_[uz(f)]), X_BX);
  }

  void write_inertial(const std::string& name, double mass, const Vector3d& com,
                      const Matrix3d& I_c, const std::string& pad) {
    const Principal p = principal(I_c);
    check_body_inertia(name, false, mass, p.moments);
    out_ << pad << "<inertial" << attr("pos", vec3(com));
    if (options_.inertia_form == InertiaForm::kFull) {
      out_ << attr("mass", num(mass))
           << attr("fullinertia",
                   nums({I_c(0, 0), I_c(1, 1), I_c(2, 2), I_c(0, 1), I_c(0, 2), I_c(1, 2)}));
    } else {
      out_ << attr("quat", quat(p.axes)) << attr("mass", num(mass))
           << attr("diaginertia", vec3(p.moments));
    }
    out_ << "/>\n";
  }

  // The inertial of group h: the model's body inertia when the body is not split,
  // else the sum of the group's links, in the head's frame.
  void write_group_inertial(int h, const std::string& name, const std::string& pad) {
    const int b = model_.frame_body[uz(h)];
    if (!split_[uz(b)]) {
      if (model_.body_mass[uz(b)] > 0.0) {
        write_inertial(name, model_.body_mass[uz(b)], model_.body_com[uz(b)],
                       model_.body_inertia_c[uz(b)], pad);
      }
      return;
    }
    wm::SpatialInertia I;  // about the body origin, body axes
    for (int f = 0; f < model_.n_frames(); ++f) {
      if (group_[uz(f)] == h) {
        I += model_.frame_inertia[uz(f)];
      }
    }
    if (!(I.m > 0.0)) {
      return;
    }
    const Vector3d c = I.h / I.m;
    const Matrix3d I_c = I.I - I.m * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose());
    const Pose X_BH = frame_pose(h);
    write_inertial(name, I.m, X_BH.R.transpose() * (c - X_BH.p), X_BH.R.transpose() * I_c * X_BH.R,
                   pad);
  }

  void write_joint(int body, const std::string& pad) {
    const auto b = uz(body);
    const int k = model_.body_joint[b];
    const auto uk = uz(k);
    const bool prismatic = model_.joint_type[uk] == wm::JointType::kPrismatic;
    const double lo = model_.joint_lower[uk];
    const double hi = model_.joint_upper[uk];
    const bool limited = std::isfinite(lo) && std::isfinite(hi) && lo < hi;
    out_ << pad << "<joint" << attr("name", model_.joint_name[uk])
         << attr("type", prismatic ? "slide" : "hinge")
         << attr("axis", vec3(model_.body_joint_axis[b]));
    if (limited) {
      out_ << attr("limited", "true") << attr("range", nums({lo, hi}));
    } else {
      out_ << attr("limited", "false");
    }
    const double armature =
        options_.armature.empty() ? model_.joint_armature[uk] : options_.armature[uk];
    out_ << attr("armature", num(armature))
         << attr("damping", num(value_or_zero(options_.damping, k)))
         << attr("frictionloss", num(value_or_zero(options_.frictionloss, k))) << "/>\n";
  }

  void write_geoms(int h, const std::string& pad) {
    for (std::size_t c = 0; c < options_.contacts.size(); ++c) {
      const ContactGeometry& g = options_.contacts[c];
      const int frame = model_.frame_id(g.link);
      if (group_[uz(frame)] != h) {
        continue;
      }
      const Pose X = in_group(frame, g.position, g.rotation);
      out_ << pad << "<geom" << attr("name", geom_name(c));
      switch (g.shape) {
        case ContactShape::box:
          out_ << attr("type", "box") << attr("size", vec3(0.5 * g.size));
          break;
        case ContactShape::sphere:
          out_ << attr("type", "sphere") << attr("size", num(g.radius));
          break;
        case ContactShape::capsule:
          out_ << attr("type", "capsule") << attr("size", nums({g.radius, 0.5 * g.length}));
          break;
      }
      out_ << attr("pos", vec3(X.p)) << attr("quat", quat(X.R))
           << attr("friction", nums({g.friction, 0.005, 0.0001}))
           << " contype=\"1\" conaffinity=\"0\" condim=\"3\"/>\n";
    }
  }

  void write_sites(int h, const std::string& pad) {
    for (const Site& s : options_.sites) {
      const int frame = model_.frame_id(s.frame);
      if (group_[uz(frame)] != h) {
        continue;
      }
      const Pose X = in_group(frame, s.position, s.rotation);
      out_ << pad << "<site" << attr("name", s.name) << attr("pos", vec3(X.p))
           << attr("quat", quat(X.R)) << " size=\"0.005\"/>\n";
    }
  }

  void write_sensors() {
    std::ostringstream sensors;
    for (const Site& s : options_.sites) {
      const std::string site = attr("site", s.name);
      if (s.sensor == SiteSensor::kForceTorque) {
        sensors << "    <force" << attr("name", s.name + "_force") << site << "/>\n"
                << "    <torque" << attr("name", s.name + "_torque") << site << "/>\n";
      } else if (s.sensor == SiteSensor::kImu) {
        sensors << "    <framequat" << attr("name", s.name + "_quat") << " objtype=\"site\""
                << attr("objname", s.name) << "/>\n"
                << "    <gyro" << attr("name", s.name + "_gyro") << site << "/>\n"
                << "    <accelerometer" << attr("name", s.name + "_accelerometer") << site
                << "/>\n";
      }
    }
    if (!sensors.str().empty()) {
      out_ << "  <sensor>\n" << sensors.str() << "  </sensor>\n";
    }
  }

  void write_contents(int h, int depth, const std::string& pad) {
    write_geoms(h, pad);
    write_sites(h, pad);
    for (const int child : children_[uz(h)]) {
      write_group(child, depth);
    }
  }

  void write_group(int h, int depth) {
    const int b = model_.frame_body[uz(h)];
    const bool body_head = body_head_[uz(b)] == h;
    const std::string pad(uz(2 * depth), ' ');
    const std::string inner = pad + "  ";
    const std::string& name = model_.frame_name[uz(h)];
    if (b == 0 && body_head && !floating_ && name == "world") {
      // A fixed root named "world" (the URDF convention for a fixed base) is
      // MuJoCo's world body itself: the names would clash, and it does not move.
      // The world body cannot carry an inertial: the root's lumped mass (static,
      // no part of the dynamics, but of the total mass) goes on a welded body.
      if (model_.body_mass[0] > 0.0) {
        out_ << pad << "<body name=\"world_inertial\">\n";
        write_group_inertial(h, name, inner);
        out_ << pad << "</body>\n";
      }
      write_contents(h, depth, pad);
      return;
    }
    out_ << pad << "<body" << attr("name", name);
    if (b == 0 && body_head) {
      out_ << attr("pos", "0 0 0");
    } else {
      // seen from the head of the group of the link it hangs from
      const int parent_group = group_[uz(model_.frame_parent[uz(h)])];
      const Pose X = body_head ? Pose{model_.joint_p_PJ[uz(b)], model_.joint_R_PJ[uz(b)]}
                               : frame_pose(h);  // joint frame at q = 0 / welded link
      const Pose X_P = relative(frame_pose(parent_group), X);
      out_ << attr("pos", vec3(X_P.p)) << attr("quat", quat(X_P.R));
    }
    out_ << ">\n";
    if (body_head) {
      const bool moving = b > 0 || floating_;
      if (moving) {  // MuJoCo's check applies to the body and what is welded to it
        const Principal p = principal(model_.body_inertia_c[uz(b)]);
        check_body_inertia(model_.body_name[uz(b)], true, model_.body_mass[uz(b)], p.moments);
      }
      if (b == 0 && floating_) {
        out_ << inner << "<joint" << attr("name", options_.free_joint_name) << " type=\"free\""
             << " limited=\"false\" armature=\"0\" damping=\"0\" frictionloss=\"0\"/>\n";
      } else if (b > 0) {
        write_joint(b, inner);
      }
    }
    write_group_inertial(h, name, inner);
    write_contents(h, depth + 1, inner);
    out_ << pad << "</body>\n";
  }

  const wm::Model& model_;
  const MjcfOptions& options_;
  std::vector<int> body_head_;              // per body: its first link's frame
  std::vector<bool> split_;                 // per body: has welded links
  std::vector<int> group_;                  // per frame: the head frame of its MJCF body
  std::vector<std::vector<int>> children_;  // per head frame: child heads, in frame order
  bool floating_ = true;
  std::ostringstream out_;
};

}  // namespace

std::string write_mjcf(const wbi::model::Model& model, const MjcfOptions& options) {
  return Writer(model, options).write();
}

}  // namespace wbi::mjcf
