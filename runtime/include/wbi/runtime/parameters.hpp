// Typed parameters of a component, read from a YAML map.
//
// A component reads what it needs in on_configure with get() (optional, with
// a default) or require(); the runtime then calls reject_unknown(), so a key
// the component never asked for (a typo) is an error, not a silent default.
// Every error names the file, the line, the component and the key:
//   deploy/icub.yaml:14: component 'model': parameter 'rate' must be a number, got 'fast'
//   deploy/icub.yaml:15: component 'model': unknown parameter 'urdf_pth' (known: joints, urdf)
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace wbi::runtime {

class ParameterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Parameters {
 public:
  // No parameters at all.
  Parameters();
  // node: a YAML map, or null for none (anything else is an error). file: where
  // it comes from; context: who they are for, e.g. "component 'model'".
  Parameters(const YAML::Node& node, std::string file, std::string context);
  // Parses YAML text (tests, tools).
  static Parameters from_string(const std::string& yaml, const std::string& context = "parameters");
  ~Parameters();
  Parameters(const Parameters&);
  Parameters& operator=(const Parameters&);

  // Supported T: bool, int, std::int64_t, double, std::string,
  // std::vector<double>, std::vector<std::string>, std::map<std::string, double>
  // (a YAML map of names to numbers; a bad entry is named with its own line).
  template <class T>
  T get(const std::string& key, const T& fallback) const;
  template <class T>
  T require(const std::string& key) const;
  // Whether the key is given (counts as asking for it).
  bool has(const std::string& key) const;

  // The map under `key` as parameters of their own, e.g. one controller's in a
  // host's `controllers:` (context: "<context>, <key> '<name>'"); none when
  // absent. Throws ParameterError when the value is not a map.
  Parameters child(const std::string& key, const std::string& context) const;
  // This map's keys, in file order (does not count as asking for them).
  std::vector<std::string> keys() const;

  // Throws ParameterError for the first key nobody asked for.
  void reject_unknown() const;
  // "file:line: context" for messages about a key (or about the map when key is empty).
  std::string where(const std::string& key = "") const;
  // The file the parameters come from ("<string>" or "" when none), e.g. to
  // resolve relative paths.
  const std::string& file() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
  mutable std::set<std::string> asked_;
};

}  // namespace wbi::runtime
