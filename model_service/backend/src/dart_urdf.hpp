// The URDF text DART is given: the file as wbi reads it, rewritten in memory so
// that DART builds the same multibody as wbi's loader (Model).
#pragma once

#include <string>

#include "wbi/model/model.hpp"

namespace wbi::model {

// Reads urdf and returns it with
//  - <visual> and <collision> removed (DART cannot load missing meshes, and
//    geometry plays no part in the model);
//  - an explicit zero <inertial> for links without one (DART defaults them to 1 kg,
//    wbi treats them as massless);
//  - <mimic> removed (wbi's policy: a mimic joint is an independent joint; DART
//    would couple it);
//  - the joints model locks (reduced model) turned into fixed joints, their motion
//    at the locked position folded into <origin>.
// Throws std::runtime_error naming the file when it cannot be read or parsed.
std::string urdf_for_dart(const std::string& urdf, const Model& model);

}  // namespace wbi::model
