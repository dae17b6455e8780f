#include "wbi/runtime/parameters.hpp"

#include <sstream>

#include <yaml-cpp/yaml.h>

namespace wbi::runtime {

struct Parameters::Impl {
  YAML::Node node;
  std::string file;
  std::string context;
};

Parameters::Parameters() : impl_(std::make_shared<Impl>()) {}

Parameters::Parameters(const YAML::Node& node, std::string file, std::string context)
    : impl_(std::make_shared<Impl>(Impl{node, std::move(file), std::move(context)})) {
  if (node && !node.IsNull() && !node.IsMap()) {
    throw ParameterError(where() + ": parameters must be a map of key: value");
  }
}

Parameters Parameters::from_string(const std::string& yaml, const std::string& context) {
  try {
    return Parameters(YAML::Load(yaml), "<string>", context);
  } catch (const YAML::Exception& error) {
    throw ParameterError("<string>:" + std::to_string(error.mark.line + 1) + ": " + context + ": " +
                         error.msg);
  }
}

Parameters::~Parameters() = default;
Parameters::Parameters(const Parameters&) = default;
Parameters& Parameters::operator=(const Parameters&) = default;

std::string Parameters::where(const std::string& key) const {
  int line = -1;
  if (impl_->node && impl_->node.IsMap()) {
    line = impl_->node.Mark().line;
    for (const auto& entry : impl_->node) {
      if (!key.empty() && entry.first.Scalar() == key) {
        line = entry.first.Mark().line;
      }
    }
  }
  std::string text = impl_->file.empty() ? std::string("<none>") : impl_->file;
  if (line >= 0) {
    text += ':';
    text += std::to_string(line + 1);
  }
  if (!impl_->context.empty()) {
    text += ": ";
    text += impl_->context;
  }
  return text;
}

const std::string& Parameters::file() const { return impl_->file; }

namespace {

template <class T>
const char* kind();
template <>
const char* kind<bool>() {
  return "a boolean (true or false)";
}
template <>
const char* kind<int>() {
  return "an integer";
}
template <>
const char* kind<std::int64_t>() {
  return "an integer";
}
template <>
const char* kind<double>() {
  return "a number";
}
template <>
const char* kind<std::string>() {
  return "a string";
}
template <>
const char* kind<std::vector<double>>() {
  return "a list of numbers";
}
template <>
const char* kind<std::vector<std::string>>() {
  return "a list of strings";
}
template <>
const char* kind<std::map<std::string, double>>() {
  return "a map of names to numbers";
}

std::string shown(const YAML::Node& node) {
  if (node.IsScalar()) {
    return "'" + node.Scalar() + "'";
  }
  if (node.IsSequence()) {
    return "a list";
  }
  if (node.IsMap()) {
    return "a map";
  }
  return "nothing";
}

template <class T>
bool convert(const YAML::Node& node, T& out) {
  if constexpr (std::is_same_v<T, std::map<std::string, double>>) {
    return false;  // a map is read entry by entry in get()
  } else if constexpr (std::is_same_v<T, std::vector<double>> ||
                       std::is_same_v<T, std::vector<std::string>>) {
    if (!node.IsSequence()) {
      return false;
    }
    out.clear();
    for (const auto& item : node) {
      typename T::value_type value;
      if (!convert(item, value)) {
        return false;
      }
      out.push_back(value);
    }
    return true;
  } else {
    if (!node.IsScalar()) {
      return false;
    }
    if constexpr (std::is_same_v<T, std::string>) {
      out = node.Scalar();
      return true;
    } else {
      if constexpr (std::is_same_v<T, bool>) {
        return YAML::convert<bool>::decode(node, out);
      } else {
        // Strict: "1.5" is not an integer, "12abc" not a number.
        std::istringstream text(node.Scalar());
        T value{};
        text >> value;
        if (text.fail() || !text.eof()) {
          return false;
        }
        out = value;
        return true;
      }
    }
  }
}

}  // namespace

bool Parameters::has(const std::string& key) const {
  asked_.insert(key);
  return impl_->node && impl_->node.IsMap() && impl_->node[key];
}

template <class T>
T Parameters::get(const std::string& key, const T& fallback) const {
  if (!has(key)) {
    return fallback;
  }
  const YAML::Node value = impl_->node[key];
  T out{};
  if constexpr (std::is_same_v<T, std::map<std::string, double>>) {
    if (value.IsMap()) {  // each entry checked, so that a bad one is named at its line
      for (const auto& entry : value) {
        double number = 0.0;
        if (!convert(entry.second, number)) {
          throw ParameterError(where(key) + ": parameter '" + key + "', entry '" +
                               entry.first.Scalar() + "' (line " +
                               std::to_string(entry.first.Mark().line + 1) +
                               ") must be a number, got " + shown(entry.second));
        }
        out[entry.first.Scalar()] = number;
      }
      return out;
    }
  }
  if (!convert(value, out)) {
    throw ParameterError(where(key) + ": parameter '" + key + "' must be " + kind<T>() + ", got " +
                         shown(value));
  }
  return out;
}

template <class T>
T Parameters::require(const std::string& key) const {
  if (!has(key)) {
    throw ParameterError(where() + ": missing parameter '" + key + "' (" + kind<T>() + ")");
  }
  return get<T>(key, T{});
}

Parameters Parameters::child(const std::string& key, const std::string& context) const {
  if (!has(key)) {
    return Parameters(YAML::Node(), impl_->file, impl_->context + ", " + context);
  }
  const YAML::Node value = impl_->node[key];
  if (!value.IsMap()) {
    throw ParameterError(where(key) + ": parameter '" + key + "' must be a map, got " +
                         shown(value));
  }
  return Parameters(value, impl_->file, impl_->context + ", " + context);
}

std::vector<std::string> Parameters::keys() const {
  std::vector<std::string> out;
  if (impl_->node && impl_->node.IsMap()) {
    for (const auto& entry : impl_->node) {
      out.push_back(entry.first.Scalar());
    }
  }
  return out;
}

void Parameters::reject_unknown() const {
  if (!impl_->node || !impl_->node.IsMap()) {
    return;
  }
  for (const auto& entry : impl_->node) {
    const std::string key = entry.first.Scalar();
    if (asked_.count(key) == 0) {
      std::string known;
      for (const auto& name : asked_) {
        known += known.empty() ? "" : ", ";
        known += name;
      }
      throw ParameterError(where(key) + ": unknown parameter '" + key +
                           "' (known: " + (known.empty() ? std::string("none") : known) + ")");
    }
  }
}

#define WBI_PARAMETER_TYPE(T)                                        \
  template T Parameters::get<T>(const std::string&, const T&) const; \
  template T Parameters::require<T>(const std::string&) const;

WBI_PARAMETER_TYPE(bool)
WBI_PARAMETER_TYPE(int)
WBI_PARAMETER_TYPE(std::int64_t)
WBI_PARAMETER_TYPE(double)
WBI_PARAMETER_TYPE(std::string)
WBI_PARAMETER_TYPE(std::vector<double>)
WBI_PARAMETER_TYPE(std::vector<std::string>)
using NumberMap = std::map<std::string, double>;  // the macro cannot take the comma
WBI_PARAMETER_TYPE(NumberMap)

#undef WBI_PARAMETER_TYPE

}  // namespace wbi::runtime
