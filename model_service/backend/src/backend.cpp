// The model backends by name (wbi::Registry): the one place that maps a
// backend name to its implementation.
#include "wbi/model/backend.hpp"

#include <stdexcept>

#include <wbi/registry.hpp>

#include "wbi_backend.hpp"
#ifdef WBI_WITH_DART
#include "dart_backend.hpp"
#endif

namespace wbi::model {

namespace {

using BackendRegistry = Registry<ModelBackend, const std::string&, const LoadOptions&>;

const BackendRegistry& backends() {
  static const BackendRegistry registry = [] {
    BackendRegistry r("model backend");
    // make_wbi_backend is overloaded (a file, or a model already loaded): the file one.
    r.add(
        "wbi",
        [](const std::string& urdf, const LoadOptions& options) {
          return make_wbi_backend(urdf, options);
        },
        "the project's own rigid-body library (wbi::model)");
#ifdef WBI_WITH_DART
    r.add("dart", make_dart_backend, "DART 6 (dartsim), loaded from the same URDF");
#endif
    return r;
  }();
  return registry;
}

}  // namespace

std::vector<std::string> model_backend_names() { return backends().names(); }

void check_model_backend_name(std::string_view name) {
  if (!backends().contains(std::string(name)) && name == "dart") {
    throw std::invalid_argument(
        "model backend 'dart' is not built: DART 6 was not found when wbi was configured "
        "(scripts/install-deps --with-dart, then reconfigure); known: " +
        backends().names_text());
  }
  backends().description(std::string(name));  // throws naming the known backends
}

std::unique_ptr<ModelBackend> make_model_backend(std::string_view name, const std::string& urdf,
                                                 const LoadOptions& options) {
  check_model_backend_name(name);
  return backends().create(std::string(name), urdf, options);
}

}  // namespace wbi::model
