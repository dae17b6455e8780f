// The model side of the MJCF export (mjcf_export.hpp).
#include <wbi/model_inspect/mjcf_export.hpp>

#include <fstream>
#include <stdexcept>

namespace wbi::model_inspect {

MjcfExport mjcf_export_from_urdf(const std::string& urdf_file, model::LoadOptions load) {
  load.repair_inertia = true;
  return {model::load_urdf_file(urdf_file, load), mjcf::MjcfOptions{}};
}

int mjcf_body_count(const MjcfExport& exported) {
  return exported.model.n_bodies + static_cast<int>(exported.options.welded_links.size());
}

void write_export_summary(std::ostream& out, const MjcfExport& exported) {
  const model::Model& m = exported.model;
  out << m.name << ", " << m.n_joints << " joints, " << mjcf_body_count(exported) << " bodies, "
      << (m.floating_base ? "free-floating" : "fixed base") << ", total mass " << m.total_mass
      << " kg";
}

void save_text_file(const std::string& text, const std::string& file) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    throw std::runtime_error("cannot write '" + file + "'");
  }
}

}  // namespace wbi::model_inspect
