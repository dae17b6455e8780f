// The "dart" backend: DART 6 (dart::dynamics::Skeleton) loaded from the same
// URDF, answering in the mixed representation. Built only with WBI_WITH_DART.
#pragma once

#include <memory>

#include "wbi/model/backend.hpp"

namespace wbi::model {

std::unique_ptr<ModelBackend> make_dart_backend(const std::string& urdf,
                                                const LoadOptions& options);

}  // namespace wbi::model
