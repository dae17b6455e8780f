// What a loaded model is made of, as `wbi model info` reports it: base kind,
// joints in the order of q and ν with their limits and armature, locked joints of
// a reduced model, bodies after lumping fixed joints with the frames on each, and
// the total mass. Kept out of the command line so that other tools (and tests)
// get the same report from a Model.
#pragma once

#include <ostream>
#include <string>

#include <nlohmann/json.hpp>
#include <wbi/model/model.hpp>

namespace wbi::model_inspect {

// "revolute", "continuous" or "prismatic": the kind of the model's joint k.
std::string joint_type_name(const model::Model& model, int joint);

// The report as JSON: keys name, file, base ("floating"|"fixed"), root_link, nq,
// nv, total_mass, joints [{name, type, body, parent_body, lower, upper, velocity,
// effort, armature, mimic?}], locked_joints [{name, position}], bodies [{name,
// parent, mass, com, frames}], frames [{name, body, position}]. Infinite limits
// are null.
nlohmann::json info_json(const model::Model& model);

// The report as aligned text, one joint and one body per line (what `wbi model
// info` prints without --json). Writes with `out`'s current formatting.
void write_info_text(std::ostream& out, const model::Model& model);

}  // namespace wbi::model_inspect
