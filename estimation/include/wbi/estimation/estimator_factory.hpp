// Estimators by name, with their parameters described for command lines and
// deploy files. Parameters are given by name (kebab-case, as on the command
// line) and validated with errors naming the method and the parameter.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "wbi/estimation/derivative_estimator.hpp"

namespace wbi::estimation {

struct ParameterSpec {
  std::string name;     // e.g. "velocity-window"
  std::string metavar;  // e.g. "N"
  double default_value;
  double min;  // inclusive
  double max;  // inclusive
  bool integer;
  std::string help;  // one line, with the unit
};

struct MethodInfo {
  std::string name;
  std::string summary;                    // one line
  std::vector<ParameterSpec> parameters;  // including the stream parameters
};

// Every method, the recommended one first.
const std::vector<MethodInfo>& methods();
std::vector<std::string> method_names();
// Throws std::invalid_argument naming the known methods when name is unknown.
const MethodInfo& method_info(const std::string& name);

using Parameters = std::map<std::string, double>;

// Builds the estimator `method` for `joints` joints. `given` holds the
// parameters to change from their defaults. Throws std::invalid_argument for an
// unknown method, a parameter the method does not have, or a value out of range.
std::unique_ptr<DerivativeEstimator> make_estimator(const std::string& method, Eigen::Index joints,
                                                    const Parameters& given = {});

}  // namespace wbi::estimation
