// make_model_backend: the one place that maps a backend name to its implementation.
#include "wbi/model/backend.hpp"

#include <algorithm>
#include <stdexcept>

#include "wbi_backend.hpp"
#ifdef WBI_WITH_DART
#include "dart_backend.hpp"
#endif

namespace wbi::model {

std::vector<std::string> model_backend_names() {
#ifdef WBI_WITH_DART
  return {"wbi", "dart"};
#else
  return {"wbi"};
#endif
}

void check_model_backend_name(std::string_view name) {
  const auto names = model_backend_names();
  if (std::find(names.begin(), names.end(), name) != names.end()) {
    return;
  }
  std::string available;
  for (const auto& known : names) {
    available += (available.empty() ? "" : ", ") + known;
  }
  if (name == "dart") {
    throw std::invalid_argument(
        "model backend 'dart' is not built: DART 6 was not found when wbi was configured "
        "(scripts/install-deps --with-dart, then reconfigure); available: " +
        available);
  }
  throw std::invalid_argument("unknown model backend '" + std::string(name) +
                              "' (available: " + available + ")");
}

std::unique_ptr<ModelBackend> make_model_backend(std::string_view name, const std::string& urdf,
                                                 const LoadOptions& options) {
  check_model_backend_name(name);
#ifdef WBI_WITH_DART
  if (name == "dart") {
    return make_dart_backend(urdf, options);
  }
#endif
  return make_wbi_backend(urdf, options);
}

}  // namespace wbi::model
