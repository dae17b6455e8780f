// Private to the URDF loader: the error that names the file, the raw-XML
// structure check (tinyxml2), and the checks and repair of link inertias.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include <urdf_model/link.h>

#include "wbi/model/model.hpp"

namespace wbi::model::detail {

class Error {
 public:
  explicit Error(std::string source) : source_(std::move(source)) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument("URDF '" + source_ + "': " + what);
  }

 private:
  std::string source_;
};

// What the raw XML says about one joint.
struct RawJoint {
  std::string parent, child, type;
  int order = 0;  // position in the file
  int line = 0;
};

// Structure checks on the raw XML; returns the joints by name.
std::map<std::string, RawJoint> check_structure(const std::string& xml, const Error& err);

// The mass and inertia of a link: finite, no negative moment; when strict, a
// physical inertia (positive semi-definite, triangle inequality).
void check_inertial(const urdf::Link& link, bool strict, const Error& err);

// Returns true and writes the repaired inertia when I is not physical
// (LoadOptions::repair_inertia; urdf_inertia.cpp says how).
bool repair_inertia(const Matrix3d& I, Matrix3d& repaired);

}  // namespace wbi::model::detail
