#include "dart_urdf.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <tinyxml2.h>
#include <Eigen/Geometry>

namespace wbi::model {

namespace {

using tinyxml2::XMLElement;

std::string text_of(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

Eigen::Vector3d triple(const XMLElement* element, const char* attribute) {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  if (element == nullptr || element->Attribute(attribute) == nullptr) {
    return v;
  }
  std::istringstream in(element->Attribute(attribute));
  in >> v.x() >> v.y() >> v.z();
  return v;
}

// URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d from_rpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d to_rpy(const Eigen::Matrix3d& R) {
  const double pitch = std::atan2(-R(2, 0), std::hypot(R(0, 0), R(1, 0)));
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

void remove_children(XMLElement* parent, const char* name) {
  while (XMLElement* child = parent->FirstChildElement(name)) {
    parent->DeleteChild(child);
  }
}

// <joint> of a locked joint → fixed, origin ← origin · motion(position).
void lock_joint(XMLElement* joint, double position) {
  const std::string type = joint->Attribute("type");
  XMLElement* origin = joint->FirstChildElement("origin");
  if (origin == nullptr) {
    origin = joint->InsertNewChildElement("origin");
  }
  const Eigen::Vector3d xyz = triple(origin, "xyz");
  const Eigen::Matrix3d R = from_rpy(triple(origin, "rpy"));
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  // URDF default
  if (const XMLElement* a = joint->FirstChildElement("axis")) {
    axis = triple(a, "xyz").normalized();
  }
  Eigen::Vector3d p = xyz;
  Eigen::Matrix3d R_new = R;
  if (type == "prismatic") {
    p += R * (axis * position);
  } else {
    R_new = R * Eigen::AngleAxisd(position, axis).toRotationMatrix();
  }
  const Eigen::Vector3d rpy = to_rpy(R_new);
  origin->SetAttribute("xyz",
                       (text_of(p.x()) + " " + text_of(p.y()) + " " + text_of(p.z())).c_str());
  origin->SetAttribute(
      "rpy", (text_of(rpy.x()) + " " + text_of(rpy.y()) + " " + text_of(rpy.z())).c_str());
  joint->SetAttribute("type", "fixed");
  remove_children(joint, "axis");
  remove_children(joint, "limit");
  remove_children(joint, "dynamics");
}

}  // namespace

std::string urdf_for_dart(const std::string& urdf, const Model& model) {
  std::ifstream file(urdf);
  if (!file) {
    throw std::invalid_argument(urdf + ": cannot open");
  }
  std::ostringstream text;
  text << file.rdbuf();
  tinyxml2::XMLDocument document;
  if (document.Parse(text.str().c_str()) != tinyxml2::XML_SUCCESS) {
    throw std::runtime_error(urdf + ": XML error: " + document.ErrorStr());
  }
  XMLElement* robot = document.FirstChildElement("robot");
  if (robot == nullptr) {
    throw std::runtime_error(urdf + ": no <robot> element");
  }
  for (XMLElement* link = robot->FirstChildElement("link"); link != nullptr;
       link = link->NextSiblingElement("link")) {
    remove_children(link, "visual");
    remove_children(link, "collision");
    if (link->FirstChildElement("inertial") == nullptr) {
      XMLElement* inertial = link->InsertNewChildElement("inertial");
      inertial->InsertNewChildElement("mass")->SetAttribute("value", "0");
      XMLElement* inertia = inertial->InsertNewChildElement("inertia");
      for (const char* entry : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}) {
        inertia->SetAttribute(entry, "0");
      }
    }
  }
  for (XMLElement* joint = robot->FirstChildElement("joint"); joint != nullptr;
       joint = joint->NextSiblingElement("joint")) {
    remove_children(joint, "mimic");
    const char* name = joint->Attribute("name");
    for (std::size_t k = 0; name != nullptr && k < model.locked_joint_name.size(); ++k) {
      if (model.locked_joint_name[k] == name) {
        lock_joint(joint, model.locked_joint_position[k]);
      }
    }
  }
  tinyxml2::XMLPrinter printer;
  document.Print(&printer);
  return printer.CStr();
}

}  // namespace wbi::model
