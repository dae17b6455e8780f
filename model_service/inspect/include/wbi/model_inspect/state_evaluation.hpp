// The model evaluated at one state given as JSON, as `wbi model eval` prints it:
// M, h, G, CoM, centroidal momentum and, per requested frame, its pose, Jacobian
// and J̇ν, computed by any model backend. A caller may list the joints in its own
// order; the results then follow that order (the base's six coordinates first),
// so a tool in another language can compare without knowing wbi's joint order.
//
// State keys (all optional): q, dq (in the order of `joints` when given, else the
// model's), base_position [3], base_quaternion [w,x,y,z], base_velocity [6:
// linear, angular, world axes], gravity [3] (default [0,0,-9.81]), frames
// [names], joints [every joint, in the caller's order].
#pragma once

#include <string>

#include <nlohmann/json.hpp>
#include <wbi/model/backend.hpp>

namespace wbi::model_inspect {

// The JSON object in `where`, a file name or "-" for standard input. Throws
// std::runtime_error naming `where`: the file cannot be opened, the text is not
// JSON, or it is not an object.
nlohmann::json read_state(const std::string& where);

// The backend's model evaluated at `state`. Output keys: backend, joints,
// mass_matrix, bias_forces, gravity_forces, total_mass, com, centroidal_momentum
// (com and centroidal_momentum null for a massless model), frames {name:
// {transform 4x4, jacobian 6x(n+6), dJnu [6]}}; matrices are arrays of rows.
// Throws std::runtime_error "state: ..." naming the bad key (unknown key, wrong
// size, not a number, unknown or repeated joint, a joint missing from `joints`,
// a base key on a fixed-base model, a quaternion that is not unit, an unknown
// frame); what the backend throws (std::invalid_argument) otherwise.
nlohmann::json evaluate_state(model::ModelBackend& backend, const nlohmann::json& state);

}  // namespace wbi::model_inspect
