// The catalog: a process's registries (wbi/registry.hpp), one per kind of
// thing made by name: component types, controller types, simulation
// engines. Plugins (wbi/plugin.hpp) add to it; the program makes what a
// deploy file names from it. A registry kind is a class derived from
// wbi::RegistryBase, default-constructible, with `static constexpr const char*
// kKind` (e.g. "controller type"); the catalog makes it at its first use, so
// a plugin may bring a kind of its own.
//
// Lifetime: the catalog outlives everything made from it, and the plugins
// whose code it holds are never unloaded.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "wbi/registry.hpp"

namespace wbi {

class Catalog {
 public:
  Catalog() = default;
  Catalog(const Catalog&) = delete;
  Catalog& operator=(const Catalog&) = delete;

  // The registry of kind R, made on first use.
  template <class R>
  R& registry() {
    auto& slot = registries_[R::kKind];
    if (!slot) {
      auto made = std::make_unique<R>();
      made->set_provider(provider_);
      slot = std::move(made);
    }
    auto* typed = dynamic_cast<R*>(slot.get());
    if (!typed) {
      throw std::logic_error(std::string("two registry classes claim the kind '") + R::kKind + "'");
    }
    return *typed;
  }

  // Every registry made so far, by kind.
  std::vector<const RegistryBase*> registries() const {
    std::vector<const RegistryBase*> out;
    for (const auto& [kind, registry] : registries_) {
      out.push_back(registry.get());
    }
    return out;
  }

  // What is added from now on comes from `provider` (every registry, and
  // those made later). The plugin loader sets it around each plugin.
  void set_provider(const std::string& provider) {
    provider_ = provider;
    for (auto& [kind, registry] : registries_) {
      registry->set_provider(provider);
    }
  }
  const std::string& provider() const { return provider_; }

  // A step to run once every plugin of the process is in, e.g. a component
  // type for each controller type, whichever plugin brought it.
  void after_loading(std::function<void(Catalog&)> step) {
    pending_.push_back({provider_, std::move(step)});
  }
  // Runs the steps (each once), each attributed to the provider that asked for it.
  void finish_loading() {
    auto steps = std::move(pending_);
    pending_.clear();
    const std::string current = provider_;
    for (auto& step : steps) {
      set_provider(step.provider);
      step.run(*this);
    }
    set_provider(current);
  }

 private:
  std::map<std::string, std::unique_ptr<RegistryBase>> registries_;
  struct Step {
    std::string provider;
    std::function<void(Catalog&)> run;
  };
  std::vector<Step> pending_;
  std::string provider_;
};

}  // namespace wbi
