// Component types by name, so that a host process creates the components a
// deploy file lists. Component libraries export a registration function
// (e.g. wbi::model_service::register_components(Registry&)) that the host
// calls explicitly: no static-initialisation tricks that the linker may drop.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "wbi/runtime/component.hpp"

namespace wbi::runtime {

class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Component>()>;

  // Throws std::invalid_argument when the type is already registered.
  void add(const std::string& type, Factory factory, std::string description = "");
  template <class C>
  void add(const std::string& type, std::string description = "") {
    add(
        type, [] { return std::make_unique<C>(); }, std::move(description));
  }

  // Throws std::invalid_argument naming the type and listing the known ones.
  std::unique_ptr<Component> create(const std::string& type) const;
  bool contains(const std::string& type) const { return entries_.count(type) != 0; }
  std::vector<std::string> types() const;
  const std::string& description(const std::string& type) const;

 private:
  struct Entry {
    Factory factory;
    std::string description;
  };
  std::map<std::string, Entry> entries_;
};

}  // namespace wbi::runtime
