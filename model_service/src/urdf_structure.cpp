// The URDF loader's first pass over the raw XML (tinyxml2): syntax errors with
// their line, and the tree's structure (one root, no loops, no dangling links).
#include <map>
#include <set>
#include <string>

#include <tinyxml2.h>

#include "urdf_detail.hpp"

namespace wbi::model::detail {

namespace {

std::string line_of(const tinyxml2::XMLElement* e) {
  return " (line " + std::to_string(e->GetLineNum()) + ")";
}

}  // namespace

std::map<std::string, RawJoint> check_structure(const std::string& xml, const Error& err) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS) {
    err.fail("XML error at line " + std::to_string(doc.ErrorLineNum()) + ": " + doc.ErrorStr());
  }
  const tinyxml2::XMLElement* robot = doc.RootElement();
  if (robot == nullptr || std::string(robot->Name()) != "robot") {
    err.fail("the root element is not <robot>");
  }
  std::map<std::string, int> link_line;
  for (auto* l = robot->FirstChildElement("link"); l != nullptr;
       l = l->NextSiblingElement("link")) {
    const char* name = l->Attribute("name");
    if (name == nullptr) {
      err.fail("<link> without a name" + line_of(l));
    }
    if (!link_line.emplace(name, l->GetLineNum()).second) {
      err.fail("link '" + std::string(name) + "' is defined twice" + line_of(l));
    }
  }
  if (link_line.empty()) {
    err.fail("no <link> in <robot>");
  }
  std::map<std::string, RawJoint> joints;
  std::map<std::string, std::string> parent_joint;  // child link → joint
  int order = 0;
  for (auto* j = robot->FirstChildElement("joint"); j != nullptr;
       j = j->NextSiblingElement("joint")) {
    const char* name = j->Attribute("name");
    if (name == nullptr) {
      err.fail("<joint> without a name" + line_of(j));
    }
    RawJoint raw;
    raw.order = order++;
    raw.line = j->GetLineNum();
    raw.type = j->Attribute("type") != nullptr ? j->Attribute("type") : "";
    const auto* p = j->FirstChildElement("parent");
    const auto* c = j->FirstChildElement("child");
    if (p == nullptr || p->Attribute("link") == nullptr || c == nullptr ||
        c->Attribute("link") == nullptr) {
      err.fail("joint '" + std::string(name) + "' needs <parent link=…> and <child link=…>" +
               line_of(j));
    }
    raw.parent = p->Attribute("link");
    raw.child = c->Attribute("link");
    for (const std::string& l : {raw.parent, raw.child}) {
      if (link_line.count(l) == 0) {
        err.fail("joint '" + std::string(name) + "' refers to unknown link '" + l + "'" +
                 line_of(j));
      }
    }
    if (raw.parent == raw.child) {
      err.fail("joint '" + std::string(name) + "' connects link '" + raw.parent + "' to itself" +
               line_of(j));
    }
    if (auto it = parent_joint.find(raw.child); it != parent_joint.end()) {
      err.fail("link '" + raw.child + "' is the child of two joints ('" + it->second + "' and '" +
               name + "'): kinematic loop" + line_of(j));
    }
    parent_joint[raw.child] = name;
    // the axis, checked on the raw text: a zero axis cannot be normalised
    if (const auto* axis = j->FirstChildElement("axis");
        axis != nullptr && raw.type != "fixed" && axis->Attribute("xyz") != nullptr) {
      std::istringstream in(axis->Attribute("xyz"));
      double x = 0, y = 0, z = 0;
      if (!(in >> x >> y >> z) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
        err.fail("joint '" + std::string(name) + "' has a malformed axis" + line_of(axis));
      }
      if (std::sqrt(x * x + y * y + z * z) < 1e-12) {
        err.fail("joint '" + std::string(name) + "' has a zero axis" + line_of(axis));
      }
    }
    if (!joints.emplace(name, raw).second) {
      err.fail("joint '" + std::string(name) + "' is defined twice" + line_of(j));
    }
  }
  std::vector<std::string> roots;
  for (const auto& [link, line] : link_line) {
    if (parent_joint.count(link) == 0) {
      roots.push_back(link);
    }
  }
  if (roots.empty()) {
    err.fail("no root link: the joints form a kinematic loop");
  }
  if (roots.size() > 1) {
    std::string list;
    for (const auto& r : roots) {
      list += (list.empty() ? "'" : ", '") + r + "'";
    }
    err.fail("several root links (" + list + "): the links do not form one tree");
  }
  // every link reachable from the root, else a loop
  std::map<std::string, std::vector<std::string>> children;
  for (const auto& [name, raw] : joints) {
    children[raw.parent].push_back(raw.child);
  }
  std::set<std::string> seen{roots.front()};
  std::vector<std::string> stack{roots.front()};
  while (!stack.empty()) {
    const std::string l = stack.back();
    stack.pop_back();
    for (const auto& c : children[l]) {
      if (seen.insert(c).second) {
        stack.push_back(c);
      }
    }
  }
  if (seen.size() != link_line.size()) {
    for (const auto& [link, line] : link_line) {
      if (seen.count(link) == 0) {
        err.fail("link '" + link + "' (line " + std::to_string(line) +
                 ") is not reachable from the root: kinematic loop");
      }
    }
  }
  return joints;
}

}  // namespace wbi::model::detail
