// Things made by name: the one registry mechanism of wbi, behind component
// types (wbi::runtime::Registry), simulation engines
// (wbi::sim_robot::EngineRegistry) and model backends (wbi::model). Each name
// has a factory and a one-line description; a name that is not there gets an
// error that lists the names that are. Registration is explicit (a library
// exports a function that adds its entries): no static-initialisation tricks
// that a linker may drop.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace wbi {

template <class Product, class... Args>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Product>(Args...)>;

  // `what` names an entry in errors: "component type", "engine", "model backend".
  explicit Registry(std::string what) : what_(std::move(what)) {}

  // Throws std::invalid_argument for an empty name, no factory or a name taken.
  void add(const std::string& name, Factory factory, std::string description = "") {
    if (name.empty() || !factory) {
      throw std::invalid_argument(what_ + ": empty name or no factory");
    }
    if (!entries_.emplace(name, Entry{std::move(factory), std::move(description)}).second) {
      throw std::invalid_argument(what_ + " '" + name + "' is already registered");
    }
  }

  // Throws std::invalid_argument naming `name` and the known names, or
  // std::runtime_error when the factory made nothing.
  std::unique_ptr<Product> create(const std::string& name, Args... args) const {
    auto product = entry(name).factory(std::forward<Args>(args)...);
    if (!product) {
      throw std::runtime_error(what_ + " '" + name + "': its factory made nothing");
    }
    return product;
  }

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

  // Throws std::invalid_argument as create() does.
  const std::string& description(const std::string& name) const { return entry(name).description; }

 private:
  struct Entry {
    Factory factory;
    std::string description;
  };

  const Entry& entry(const std::string& name) const {
    const auto it = entries_.find(name);
    if (it == entries_.end()) {
      throw std::invalid_argument("unknown " + what_ + " '" + name + "' (known: " + names_text() +
                                  ")");
    }
    return it->second;
  }

  std::string what_;
  std::map<std::string, Entry> entries_;
};

}  // namespace wbi
