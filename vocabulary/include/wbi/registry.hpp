// Things made by name: the one registry mechanism of wbi, behind component
// types (wbi::runtime::Registry), controller types
// (wbi::controllers::ControllerRegistry), simulation engines
// (wbi::sim_robot::EngineRegistry) and model backends (wbi::model). Each name
// has a factory, a one-line description and its provider (the plugin that
// registered it, wbi/plugin.hpp); a name that is not there gets an error that
// lists the names that are. Registration is explicit (a plugin's or a
// library's function adds its entries): no static-initialisation tricks that a
// linker may drop.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace wbi {

// What every registry shows, whatever it makes: names, descriptions and
// providers (for --help, `wbi plugins` and the errors of a name taken twice).
class RegistryBase {
 public:
  struct Listing {
    std::string name, description, provider;
  };

  virtual ~RegistryBase() = default;

  // "component type", "controller type", "engine", "model backend".
  const std::string& what() const { return what_; }
  // Entries added from now on come from `provider` (a plugin's file; "" for
  // the program itself). Set by the plugin loader around each registration.
  void set_provider(std::string provider) { provider_ = std::move(provider); }

  bool contains(const std::string& name) const { return entries_.count(name) != 0; }

  std::vector<std::string> names() const {  // sorted
    std::vector<std::string> out;
    for (const auto& named : entries_) {
      out.push_back(named.first);
    }
    return out;
  }

  // "a, b, c", or "none".
  std::string names_text() const {
    std::string text;
    for (const auto& named : entries_) {
      text += (text.empty() ? "" : ", ") + named.first;
    }
    return text.empty() ? "none" : text;
  }

  std::vector<Listing> listing() const {  // sorted by name
    std::vector<Listing> out;
    for (const auto& [name, entry] : entries_) {
      out.push_back({name, entry.description, entry.provider});
    }
    return out;
  }

  // Throws std::invalid_argument naming `name` and the known names.
  const std::string& description(const std::string& name) const { return meta(name).description; }
  const std::string& provider(const std::string& name) const { return meta(name).provider; }

 protected:
  explicit RegistryBase(std::string what) : what_(std::move(what)) {}
  RegistryBase(const RegistryBase&) = default;
  RegistryBase& operator=(const RegistryBase&) = default;
  RegistryBase(RegistryBase&&) = default;
  RegistryBase& operator=(RegistryBase&&) = default;

  struct Meta {
    std::string description, provider;
  };

  // Throws std::invalid_argument for a name taken, naming both providers.
  void add_meta(const std::string& name, std::string description) {
    const auto [at, added] = entries_.emplace(name, Meta{std::move(description), provider_});
    if (!added) {
      throw std::invalid_argument(what_ + " '" + name + "' is registered twice: by " +
                                  provider_text(at->second.provider) + " and by " +
                                  provider_text(provider_));
    }
  }

  const Meta& meta(const std::string& name) const {
    const auto it = entries_.find(name);
    if (it == entries_.end()) {
      throw std::invalid_argument("unknown " + what_ + " '" + name + "' (known: " + names_text() +
                                  ")");
    }
    return it->second;
  }

 private:
  static std::string provider_text(const std::string& provider) {
    return provider.empty() ? std::string("the program itself") : provider;
  }

  std::string what_;
  std::string provider_;
  std::map<std::string, Meta> entries_;
};

template <class Product, class... Args>
class Registry : public RegistryBase {
 public:
  using Factory = std::function<std::unique_ptr<Product>(Args...)>;

  // `what` names an entry in errors: "component type", "engine", "model backend".
  explicit Registry(std::string what) : RegistryBase(std::move(what)) {}

  // Throws std::invalid_argument for an empty name, no factory or a name
  // taken (naming both providers).
  void add(const std::string& name, Factory factory, std::string description = "") {
    if (name.empty() || !factory) {
      throw std::invalid_argument(what() + ": empty name or no factory");
    }
    add_meta(name, std::move(description));
    factories_.emplace(name, std::move(factory));
  }

  // Throws std::invalid_argument naming `name` and the known names, or
  // std::runtime_error when the factory made nothing.
  std::unique_ptr<Product> create(const std::string& name, Args... args) const {
    meta(name);  // unknown: the error that lists the known names
    auto product = factories_.at(name)(std::forward<Args>(args)...);
    if (!product) {
      throw std::runtime_error(what() + " '" + name + "': its factory made nothing");
    }
    return product;
  }

 private:
  std::map<std::string, Factory> factories_;
};

}  // namespace wbi
