#include "wbi/runtime/registry.hpp"

#include <stdexcept>

namespace wbi::runtime {

void Registry::add(const std::string& type, Factory factory, std::string description) {
  if (type.empty() || !factory) {
    throw std::invalid_argument("component type: empty name or no factory");
  }
  if (!entries_.emplace(type, Entry{std::move(factory), std::move(description)}).second) {
    throw std::invalid_argument("component type '" + type + "' is already registered");
  }
}

std::vector<std::string> Registry::types() const {
  std::vector<std::string> names;
  for (const auto& entry : entries_) {
    names.push_back(entry.first);
  }
  return names;
}

std::unique_ptr<Component> Registry::create(const std::string& type) const {
  const auto it = entries_.find(type);
  if (it == entries_.end()) {
    std::string known;
    for (const auto& entry : entries_) {
      known += known.empty() ? "" : ", ";
      known += entry.first;
    }
    throw std::invalid_argument("unknown component type '" + type +
                                "' (known: " + (known.empty() ? std::string("none") : known) + ")");
  }
  auto component = it->second.factory();
  if (!component) {
    throw std::runtime_error("component type '" + type + "': factory returned nothing");
  }
  return component;
}

const std::string& Registry::description(const std::string& type) const {
  const auto it = entries_.find(type);
  if (it == entries_.end()) {
    throw std::invalid_argument("unknown component type '" + type + "'");
  }
  return it->second.description;
}

}  // namespace wbi::runtime
