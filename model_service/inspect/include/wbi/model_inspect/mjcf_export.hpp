// The model side of `wbi model mjcf`: a model and the MJCF options it is written
// with, loaded from a URDF so that MuJoCo accepts it, and what is said about the
// result. The robot-config case (what the MuJoCo engine loads) is built by
// wbi::mujoco_sim::robot_model/robot_mjcf (components/mujoco_sim), which sits
// above this folder; it fills the same MjcfExport.
#pragma once

#include <ostream>
#include <string>

#include <wbi/mjcf/mjcf.hpp>
#include <wbi/model/model.hpp>
#include <wbi/model/urdf.hpp>

namespace wbi::model_inspect {

struct MjcfExport {
  model::Model model;
  mjcf::MjcfOptions options;
};

// The URDF loaded with `load` and LoadOptions::repair_inertia on (MuJoCo's compiler
// rejects non-physical link inertias; the repaired links are listed in
// model.repaired_inertia_links), default MJCF options. Throws what the loader
// throws (std::invalid_argument naming the file).
MjcfExport mjcf_export_from_urdf(const std::string& urdf_file, model::LoadOptions load);

// Bodies MuJoCo will have besides the world: the model's bodies after lumping
// fixed joints, plus the links welded back as bodies of their own.
int mjcf_body_count(const MjcfExport& exported);

// "NAME, J joints, B bodies, free-floating|fixed base, total mass M kg", written
// with `out`'s current formatting.
void write_export_summary(std::ostream& out, const MjcfExport& exported);

// Writes `text` to `file` byte for byte. Throws std::runtime_error "cannot write
// 'FILE'".
void save_text_file(const std::string& text, const std::string& file);

}  // namespace wbi::model_inspect
