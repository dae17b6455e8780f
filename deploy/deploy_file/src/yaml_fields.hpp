// Reads the fields of a deploy file's YAML; every mistake is one
// std::runtime_error "FILE:LINE: field: what" (no line for a missing node).
// One set of checks for the whole format (deploy_file.hpp): the launcher,
// wbi_host and the wbi tools all see the same message for the same mistake.
#pragma once

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace wbi::deploy::detail {

class YamlFields {
 public:
  explicit YamlFields(std::string file) : file_(std::move(file)) {}

  const std::string& file() const { return file_; }

  // "FILE:LINE" of a node, or "FILE" for one that is not there.
  std::string where(const YAML::Node& node) const;

  [[noreturn]] void fail(const YAML::Node& node, const std::string& field,
                         const std::string& what) const;

  // A mapping whose keys are all in `allowed`; else names the first other key.
  void only_keys(const YAML::Node& map, const std::string& field,
                 const std::set<std::string>& allowed) const;

  template <class T>
  T scalar(const YAML::Node& node, const std::string& field, const std::string& expected) const {
    if (!node.IsScalar()) {
      fail(node, field, "expected " + expected);
    }
    try {
      return node.as<T>();
    } catch (const YAML::Exception&) {
      fail(node, field, "expected " + expected + ", got '" + node.Scalar() + "'");
    }
  }

  std::string non_empty_text(const YAML::Node& node, const std::string& field) const;
  std::map<std::string, std::string> string_map(const YAML::Node& node,
                                                const std::string& field) const;
  // `what` names the list in the error ("a list", "a list of addresses").
  std::vector<std::string> string_list(const YAML::Node& node, const std::string& field,
                                       const std::string& what = "a list") const;
  std::vector<std::string> non_empty_text_list(const YAML::Node& node, const std::string& field,
                                               const std::string& what) const;

 private:
  std::string file_;
};

}  // namespace wbi::deploy::detail
