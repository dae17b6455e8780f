#include "wbi/sim_robot/engine_registry.hpp"

#include <stdexcept>

namespace wbi::sim_robot {

void EngineRegistry::add(const std::string& name, EngineFactory factory, std::string description) {
  if (!factory) {
    throw std::invalid_argument("simulation engine '" + name + "': no factory");
  }
  if (!engines_.emplace(name, Entry{std::move(factory), std::move(description)}).second) {
    throw std::invalid_argument("simulation engine '" + name + "' is already registered");
  }
}

std::unique_ptr<actuation::SimulationBackend> EngineRegistry::create(
    const std::string& name, const EngineContext& context) const {
  const auto entry = engines_.find(name);
  if (entry == engines_.end()) {
    std::string known;
    for (const auto& registered : names()) {
      known += (known.empty() ? "" : ", ") + registered;
    }
    throw std::invalid_argument("unknown engine '" + name + "' (registered: " + known + ")");
  }
  auto backend = entry->second.factory(context);
  if (!backend) {
    throw std::runtime_error("simulation engine '" + name + "' made no backend");
  }
  return backend;
}

std::vector<std::string> EngineRegistry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, entry] : engines_) {
    out.push_back(name);
  }
  return out;
}

const std::string& EngineRegistry::description(const std::string& name) const {
  const auto entry = engines_.find(name);
  if (entry == engines_.end()) {
    throw std::invalid_argument("unknown engine '" + name + "'");
  }
  return entry->second.description;
}

}  // namespace wbi::sim_robot
