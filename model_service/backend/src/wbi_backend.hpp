// The "wbi" backend: wbi::model's free functions on one Model + Data. Each call
// forwards to exactly one algorithm (plus forward kinematics for frame queries,
// skipped when the previous call left the kinematics of the same q in Data), so
// choosing the interface costs one virtual call and a comparison of q.
#pragma once

#include <memory>

#include "wbi/model/backend.hpp"

namespace wbi::model {

std::unique_ptr<ModelBackend> make_wbi_backend(const std::string& urdf, const LoadOptions& options);

}  // namespace wbi::model
