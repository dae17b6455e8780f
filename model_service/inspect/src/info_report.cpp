// The info report of a model (info_report.hpp): JSON and text.
#include <wbi/model_inspect/info_report.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>

#include "eigen_json.hpp"

namespace wbi::model_inspect {

namespace {

using nlohmann::json;
namespace wm = wbi::model;

// The names of the frames attached to body i, in frame order.
json frames_on_body(const wm::Model& m, int i) {
  json frames = json::array();
  for (int f = 0; f < m.n_frames(); ++f) {
    if (m.frame_body[static_cast<std::size_t>(f)] == i) {
      frames.push_back(m.frame_name[static_cast<std::size_t>(f)]);
    }
  }
  return frames;
}

json joint_json(const wm::Model& m, int k) {
  const auto uk = static_cast<std::size_t>(k);
  const auto body = static_cast<std::size_t>(m.joint_body[uk]);
  json j;
  j["name"] = m.joint_name[uk];
  j["type"] = joint_type_name(m, k);
  j["body"] = m.body_name[body];
  j["parent_body"] = m.body_name[static_cast<std::size_t>(m.parent[body])];
  j["lower"] = detail::limit_json(m.joint_lower[uk]);
  j["upper"] = detail::limit_json(m.joint_upper[uk]);
  j["velocity"] = detail::limit_json(m.joint_velocity_limit[uk]);
  j["effort"] = detail::limit_json(m.joint_effort_limit[uk]);
  j["armature"] = m.joint_armature[uk];
  if (!m.joint_mimic[uk].joint.empty()) {
    j["mimic"] = {{"joint", m.joint_mimic[uk].joint},
                  {"multiplier", m.joint_mimic[uk].multiplier},
                  {"offset", m.joint_mimic[uk].offset},
                  {"policy", "independent joint"}};
  }
  return j;
}

json body_json(const wm::Model& m, int i) {
  const auto ui = static_cast<std::size_t>(i);
  json b;
  b["name"] = m.body_name[ui];
  b["parent"] = i == 0 ? json(nullptr) : json(m.body_name[static_cast<std::size_t>(m.parent[ui])]);
  b["mass"] = m.body_mass[ui];
  b["com"] = detail::vector_json(m.body_com[ui]);
  b["frames"] = frames_on_body(m, i);
  return b;
}

// A limit for the text report: the number, or inf/-inf.
std::string limit_text(double x) {
  std::ostringstream s;
  if (std::isfinite(x)) {
    s << x;
  } else {
    s << (x > 0 ? "inf" : "-inf");
  }
  return s.str();
}

}  // namespace

std::string joint_type_name(const wm::Model& model, int joint) {
  const auto k = static_cast<std::size_t>(joint);
  if (model.joint_type[k] == wm::JointType::kPrismatic) {
    return "prismatic";
  }
  return model.joint_continuous[k] ? "continuous" : "revolute";
}

json info_json(const wm::Model& m) {
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
    out["joints"].push_back(joint_json(m, k));
  }
  out["locked_joints"] = json::array();
  for (std::size_t k = 0; k < m.locked_joint_name.size(); ++k) {
    out["locked_joints"].push_back(
        {{"name", m.locked_joint_name[k]}, {"position", m.locked_joint_position[k]}});
  }
  out["bodies"] = json::array();
  for (int i = 0; i < m.n_bodies; ++i) {
    out["bodies"].push_back(body_json(m, i));
  }
  out["frames"] = json::array();
  for (int f = 0; f < m.n_frames(); ++f) {
    const auto uf = static_cast<std::size_t>(f);
    out["frames"].push_back({{"name", m.frame_name[uf]},
                             {"body", m.body_name[static_cast<std::size_t>(m.frame_body[uf])]},
                             {"position", detail::vector_json(m.frame_p_BF[uf])}});
  }
  return out;
}

void write_info_text(std::ostream& out, const wm::Model& m) {
  out << "model:      " << m.name << " (" << m.source << ")\n"
      << "base:       " << (m.floating_base ? "floating" : "fixed") << " (root link '"
      << m.body_name[0] << "')\n"
      << "sizes:      nq = " << m.nq << ", nv = " << m.nv << ", " << m.n_joints << " joints, "
      << m.n_bodies << " bodies, " << m.n_frames() << " frames\n"
      << "total mass: " << m.total_mass << " kg\n\njoints (in the order of q and ν):\n";
  for (int k = 0; k < m.n_joints; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    out << "  " << std::setw(3) << k << "  " << std::left << std::setw(28) << m.joint_name[uk]
        << std::setw(11) << joint_type_name(m, k) << std::right << " ["
        << limit_text(m.joint_lower[uk]) << ", " << limit_text(m.joint_upper[uk]) << "]  vel "
        << limit_text(m.joint_velocity_limit[uk]) << "  effort "
        << limit_text(m.joint_effort_limit[uk]) << "  armature "
        << limit_text(m.joint_armature[uk]);
    if (!m.joint_mimic[uk].joint.empty()) {
      out << "  (mimics " << m.joint_mimic[uk].joint << ", treated as independent)";
    }
    out << "\n";
  }
  if (!m.locked_joint_name.empty()) {
    out << "\nlocked joints:\n";
    for (std::size_t k = 0; k < m.locked_joint_name.size(); ++k) {
      out << "  " << m.locked_joint_name[k] << " = " << m.locked_joint_position[k] << "\n";
    }
  }
  out << "\nbodies (after lumping fixed joints):\n";
  for (int i = 0; i < m.n_bodies; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    out << "  " << std::left << std::setw(28) << m.body_name[ui] << std::right << " mass "
        << std::setw(10) << m.body_mass[ui] << "  frames:";
    for (const auto& frame : frames_on_body(m, i)) {
      out << " " << frame.get<std::string>();
    }
    out << "\n";
  }
}

}  // namespace wbi::model_inspect
