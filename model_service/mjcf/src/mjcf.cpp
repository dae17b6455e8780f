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

const char* integrator_name(Integrator integrator) {
  switch (integrator) {
    case Integrator::kRK4:
      return "RK4";
    case Integrator::kImplicit:
      return "implicit";
    case Integrator::kEuler:
      break;
  }
  return "Euler";
}

class Writer {
 public:
  Writer(const wm::Model& model, const MjcfOptions& options)
      : model_(model), options_(options), children_(static_cast<std::size_t>(model.n_bodies)) {
    for (int i = 1; i < model.n_bodies; ++i) {
      children_[static_cast<std::size_t>(model.parent[static_cast<std::size_t>(i)])].push_back(i);
    }
    floating_ = options.floating_base.value_or(model.floating_base);
    check_options();
  }

  std::string write() {
    out_ << "<mujoco" << attr("model", model_.name) << ">\n"
         << "  <!-- written by wbi (wbi::mjcf::write_mjcf) from " << escape(model_.source)
         << "; fixed joints lumped as the model library lumps them -->\n"
         << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n"
         << "  <option" << attr("gravity", vec3(options_.gravity))
         << attr("timestep", num(options_.timestep))
         << attr("integrator", integrator_name(options_.integrator)) << "/>\n"
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
    write_body(0, 2);
    out_ << "  </worldbody>\n</mujoco>\n";
    return out_.str();
  }

 private:
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
      const bool ok = g.shape == ContactShape::kBox      ? (g.size.array() > 0.0).all()
                      : g.shape == ContactShape::kSphere ? g.radius > 0.0
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

  // Placement in its body of something given in a frame's coordinates.
  void in_body(int frame, const Vector3d& p, const Matrix3d& R, Vector3d& p_B,
               Matrix3d& R_B) const {
    const auto f = static_cast<std::size_t>(frame);
    p_B = model_.frame_p_BF[f] + model_.frame_R_BF[f] * p;
    R_B = model_.frame_R_BF[f] * R;
  }

  void write_inertial(int body, bool moving, const std::string& pad) {
    const auto b = static_cast<std::size_t>(body);
    const double mass = model_.body_mass[b];
    if (mass <= 0.0 && !moving) {
      return;  // a massless static body: MuJoCo's default is no mass
    }
    const Principal p = principal(model_.body_inertia_c[b]);
    if (options_.inertia_form == InertiaForm::kFull) {
      check_body_inertia(model_.body_name[b], moving, mass, p.moments);
      const Matrix3d& I = model_.body_inertia_c[b];
      out_ << pad << "<inertial" << attr("pos", vec3(model_.body_com[b])) << attr("mass", num(mass))
           << attr("fullinertia", nums({I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)}))
           << "/>\n";
      return;
    }
    check_body_inertia(model_.body_name[b], moving, mass, p.moments);
    out_ << pad << "<inertial" << attr("pos", vec3(model_.body_com[b]))
         << attr("quat", quat(p.axes)) << attr("mass", num(mass))
         << attr("diaginertia", vec3(p.moments)) << "/>\n";
  }

  void write_joint(int body, const std::string& pad) {
    const auto b = static_cast<std::size_t>(body);
    const int k = model_.body_joint[b];
    const auto uk = static_cast<std::size_t>(k);
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
    out_ << attr("armature", num(value_or_zero(options_.armature, k)))
         << attr("damping", num(value_or_zero(options_.damping, k)))
         << attr("frictionloss", num(value_or_zero(options_.frictionloss, k))) << "/>\n";
  }

  void write_geoms(int body, const std::string& pad) {
    for (std::size_t c = 0; c < options_.contacts.size(); ++c) {
      const ContactGeometry& g = options_.contacts[c];
      const int frame = model_.frame_id(g.link);
      if (model_.frame_body[static_cast<std::size_t>(frame)] != body) {
        continue;
      }
      Vector3d p;
      Matrix3d R;
      in_body(frame, g.position, g.rotation, p, R);
      out_ << pad << "<geom" << attr("name", geom_name(c));
      switch (g.shape) {
        case ContactShape::kBox:
          out_ << attr("type", "box") << attr("size", vec3(0.5 * g.size));
          break;
        case ContactShape::kSphere:
          out_ << attr("type", "sphere") << attr("size", num(g.radius));
          break;
        case ContactShape::kCapsule:
          out_ << attr("type", "capsule") << attr("size", nums({g.radius, 0.5 * g.length}));
          break;
      }
      out_ << attr("pos", vec3(p)) << attr("quat", quat(R))
           << attr("friction", nums({g.friction, 0.005, 0.0001}))
           << " contype=\"1\" conaffinity=\"0\" condim=\"3\"/>\n";
    }
  }

  void write_sites(int body, const std::string& pad) {
    for (const Site& s : options_.sites) {
      const int frame = model_.frame_id(s.frame);
      if (model_.frame_body[static_cast<std::size_t>(frame)] != body) {
        continue;
      }
      Vector3d p;
      Matrix3d R;
      in_body(frame, s.position, s.rotation, p, R);
      out_ << pad << "<site" << attr("name", s.name) << attr("pos", vec3(p))
           << attr("quat", quat(R)) << " size=\"0.005\"/>\n";
    }
  }

  void write_body(int body, int depth) {
    const auto b = static_cast<std::size_t>(body);
    const std::string pad(static_cast<std::size_t>(2 * depth), ' ');
    const std::string inner = pad + "  ";
    if (body == 0 && !floating_ && model_.body_name[0] == "world") {
      // A fixed root named "world" (the URDF convention for a fixed base) is
      // MuJoCo's world body itself: the names would clash, and it does not move.
      // The world body cannot carry an inertial: the root's lumped mass (static,
      // no part of the dynamics, but of the total mass) goes on a welded body.
      if (model_.body_mass[0] > 0.0) {
        out_ << pad << "<body name=\"world_inertial\">\n";
        write_inertial(0, false, inner);
        out_ << pad << "</body>\n";
      }
      write_geoms(0, pad);
      write_sites(0, pad);
      for (const int child : children_[b]) {
        write_body(child, depth);
      }
      return;
    }
    out_ << pad << "<body" << attr("name", model_.body_name[b]);
    if (body > 0) {  // the body frame is the joint frame at q = 0
      out_ << attr("pos", vec3(model_.joint_p_PJ[b])) << attr("quat", quat(model_.joint_R_PJ[b]));
    } else {
      out_ << attr("pos", "0 0 0");
    }
    out_ << ">\n";
    const bool moving = body > 0 || floating_;
    if (body == 0 && floating_) {
      out_ << inner << "<joint" << attr("name", options_.free_joint_name) << " type=\"free\""
           << " limited=\"false\" armature=\"0\" damping=\"0\" frictionloss=\"0\"/>\n";
    } else if (body > 0) {
      write_joint(body, inner);
    }
    write_inertial(body, moving, inner);
    write_geoms(body, inner);
    write_sites(body, inner);
    for (const int child : children_[b]) {
      write_body(child, depth + 1);
    }
    out_ << pad << "</body>\n";
  }

  const wm::Model& model_;
  const MjcfOptions& options_;
  std::vector<std::vector<int>> children_;
  bool floating_ = true;
  std::ostringstream out_;
};

}  // namespace

std::string write_mjcf(const wbi::model::Model& model, const MjcfOptions& options) {
  return Writer(model, options).write();
}

}  // namespace wbi::mjcf
