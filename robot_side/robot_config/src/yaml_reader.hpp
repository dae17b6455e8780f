// Typed reads from a yaml-cpp tree whose every error is one line
// "context:line: key: what" (the line from the node's Mark()).
#pragma once

#include <initializer_list>
#include <stdexcept>
#include <string>

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>

namespace wbi::robot_config {

class YamlReader {
 public:
  explicit YamlReader(std::string context) : context_(std::move(context)) {}

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key,
                         const std::string& what) const {
    const YAML::Mark mark = at.IsDefined() ? at.Mark() : YAML::Mark::null_mark();
    const std::string line = mark.is_null() ? "" : ":" + std::to_string(mark.line + 1);
    throw std::invalid_argument(context_ + line + ": " + key + ": " + what);
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  // The key of a map entry: a string, and not given twice in `map`.
  std::string key_of(const YAML::Node& map, const YAML::Node& key, const std::string& path) const {
    if (!key.IsScalar()) {
      fail(key, path.empty() ? "<root>" : path, "a key must be a plain name");
    }
    const std::string name = key.Scalar();
    int count = 0;
    for (const auto& kv : map) {
      count += kv.first.IsScalar() && kv.first.Scalar() == name ? 1 : 0;
    }
    if (count > 1) {
      fail(key, join(path, name), "given twice");
    }
    return name;
  }

  // `node` is a map whose keys are all in `allowed`, each once.
  void check_keys(const YAML::Node& node, const std::string& path,
                  std::initializer_list<const char*> allowed) const {
    if (!node.IsMap()) {
      fail(node, path.empty() ? "<root>" : path, "expected a map");
    }
    for (const auto& kv : node) {
      const auto key = key_of(node, kv.first, path);
      bool ok = false;
      std::string list;
      for (const char* a : allowed) {
        ok = ok || key == a;
        list += list.empty() ? a : std::string(", ") + a;
      }
      if (!ok) {
        fail(kv.first, join(path, key), "unknown key (allowed: " + list + ")");
      }
    }
  }

  // The value at `node[key]` as T, when the key is present.
  template <typename T>
  bool get(const YAML::Node& node, const std::string& path, const char* key, T& out) const {
    const YAML::Node v = node[key];
    if (!v) {
      return false;
    }
    out = as<T>(v, join(path, key));
    return true;
  }

  template <typename T>
  T as(const YAML::Node& v, const std::string& key) const {
    if (!v.IsScalar()) {
      fail(v, key, std::string("expected ") + type_name<T>());
    }
    try {
      return v.as<T>();
    } catch (const YAML::Exception&) {
      fail(v, key, std::string("expected ") + type_name<T>() + ", got '" + v.Scalar() + "'");
    }
  }

  // A number ≥ 0 (allow_zero) or > 0.
  bool get_positive(const YAML::Node& node, const std::string& path, const char* key, double& out,
                    bool allow_zero) const {
    if (!get(node, path, key, out)) {
      return false;
    }
    if (!(out > 0.0 || (allow_zero && out >= 0.0))) {
      fail(node[key], join(path, key), allow_zero ? "must be >= 0" : "must be > 0");
    }
    return true;
  }

  template <int N>
  bool get_vec(const YAML::Node& node, const std::string& path, const char* key,
               Eigen::Matrix<double, N, 1>& out) const {
    const YAML::Node v = node[key];
    if (!v) {
      return false;
    }
    const std::string name = join(path, key);
    if (!v.IsSequence() || v.size() != static_cast<std::size_t>(N)) {
      fail(v, name, "expected a list of " + std::to_string(N) + " numbers");
    }
    for (int i = 0; i < N; ++i) {
      out[i] = as<double>(v[static_cast<std::size_t>(i)], name);
    }
    return true;
  }

  // node[key] when it is a list (or absent).
  YAML::Node list(const YAML::Node& node, const std::string& path, const char* key) const {
    const YAML::Node v = node[key];
    if (v && !v.IsSequence()) {
      fail(v, join(path, key), "expected a list");
    }
    return v;
  }

  // One of `names` (mapped to `values` in order).
  template <typename E>
  bool get_enum(const YAML::Node& node, const std::string& path, const char* key,
                std::initializer_list<std::pair<const char*, E>> choices, E& out) const {
    std::string v;
    if (!get(node, path, key, v)) {
      return false;
    }
    std::string list;
    for (const auto& [name, value] : choices) {
      if (v == name) {
        out = value;
        return true;
      }
      list += list.empty() ? name : std::string(", ") + name;
    }
    fail(node[key], join(path, key), "expected one of " + list + ", got '" + v + "'");
  }

  const std::string& context() const { return context_; }

 private:
  template <typename T>
  static const char* type_name() {
    if constexpr (std::is_same_v<T, bool>) {
      return "true or false";
    } else if constexpr (std::is_same_v<T, std::string>) {
      return "a string";
    } else if constexpr (std::is_integral_v<T>) {
      return "an integer";
    } else {
      return "a number";
    }
  }

  std::string context_;
};

}  // namespace wbi::robot_config
