#include "yaml_fields.hpp"

namespace wbi::deploy::detail {

std::string YamlFields::where(const YAML::Node& node) const {
  std::string where = file_;
  if (node.IsDefined()) {
    where += ':';  // not ":" + to_string(...): GCC 12's -Wrestrict false positive at -O3
    where += std::to_string(node.Mark().line + 1);
  }
  return where;
}

void YamlFields::fail(const YAML::Node& node, const std::string& field,
                      const std::string& what) const {
  std::string message = where(node);
  message += ": ";
  message += field;
  message += ": ";
  message += what;
  throw std::runtime_error(message);
}

void YamlFields::only_keys(const YAML::Node& map, const std::string& field,
                           const std::set<std::string>& allowed) const {
  if (!map.IsMap()) {
    fail(map, field, "expected a mapping");
  }
  for (const auto& entry : map) {
    const std::string key = entry.first.Scalar();
    if (allowed.count(key) == 0) {
      std::string known;
      for (const auto& name : allowed) {
        known += (known.empty() ? "" : ", ") + name;
      }
      fail(entry.first, field.empty() ? key : field + "." + key,
           "unknown key (known: " + known + ")");
    }
  }
}

std::string YamlFields::non_empty_text(const YAML::Node& node, const std::string& field) const {
  if (!node.IsScalar() || node.Scalar().empty()) {
    fail(node, field, "expected a non-empty string");
  }
  return node.Scalar();
}

std::map<std::string, std::string> YamlFields::string_map(const YAML::Node& node,
                                                          const std::string& field) const {
  if (!node.IsMap()) {
    fail(node, field, "expected a mapping of names to values");
  }
  std::map<std::string, std::string> out;
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    out[key] = scalar<std::string>(entry.second, field + "." + key, "a value");
  }
  return out;
}

std::vector<std::string> YamlFields::string_list(const YAML::Node& node, const std::string& field,
                                                 const std::string& what) const {
  if (!node.IsSequence()) {
    fail(node, field, "expected " + what);
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    out.push_back(scalar<std::string>(node[i], field + "[" + std::to_string(i) + "]", "a string"));
  }
  return out;
}

std::vector<std::string> YamlFields::non_empty_text_list(const YAML::Node& node,
                                                         const std::string& field,
                                                         const std::string& what) const {
  if (!node.IsSequence()) {
    fail(node, field, "expected " + what);
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < node.size(); ++i) {
    out.push_back(non_empty_text(node[i], field + "[" + std::to_string(i) + "]"));
  }
  return out;
}

}  // namespace wbi::deploy::detail
