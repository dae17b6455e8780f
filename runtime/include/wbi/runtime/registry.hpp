// Component types by name, so that a host process creates the components a
// deploy file lists (wbi::Registry, wbi/registry.hpp). Component libraries
// export a registration function (e.g.
// wbi::model_service::register_components(Registry&)) that a plugin calls
// (wbi/plugin.hpp; the project's own: apps/plugins/builtin).
#pragma once

#include <memory>
#include <string>

#include <wbi/registry.hpp>

#include "wbi/runtime/component.hpp"

namespace wbi::runtime {

class Registry : public wbi::Registry<Component> {
 public:
  static constexpr const char* kKind = "component type";  // its name in a wbi::Catalog
  Registry() : wbi::Registry<Component>("component type") {}

  using wbi::Registry<Component>::add;
  // add<MyComponent>("my_type", "what it does"): a default-constructed C.
  template <class C>
  void add(const std::string& type, std::string description = "") {
    add(
        type, [] { return std::make_unique<C>(); }, std::move(description));
  }
};

}  // namespace wbi::runtime
