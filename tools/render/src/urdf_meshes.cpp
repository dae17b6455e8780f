// URDF visual meshes into the MJCF (urdf_meshes.hpp).
#include "urdf_meshes.hpp"

#include <cstdio>
#include <stdexcept>

#include <urdf_parser/urdf_parser.h>

namespace wbi::render {

namespace {

namespace fs = std::filesystem;
using Eigen::Matrix3d;
using Eigen::Quaterniond;
using Eigen::Vector3d;

fs::path resolve(const std::string& name, const fs::path& urdf_dir, const fs::path& mesh_dir) {
  const std::string package = "package://";
  const std::string file = "file://";
  if (name.rfind(package, 0) == 0) {
    const std::string rest = name.substr(package.size());
    const auto slash = rest.find('/');
    const fs::path with_package = mesh_dir / rest;
    if (fs::exists(with_package) || slash == std::string::npos) {
      return with_package;
    }
    return mesh_dir / rest.substr(slash + 1);
  }
  if (name.rfind(file, 0) == 0) {
    return name.substr(file.size());
  }
  return fs::path(name).is_absolute() ? fs::path(name) : urdf_dir / name;
}

std::string numbers(std::initializer_list<double> values) {
  std::string out;
  char text[32];
  for (double v : values) {
    std::snprintf(text, sizeof text, "%.9g", v);
    if (!out.empty()) {
      out.push_back(' ');
    }
    out.append(text);
  }
  return out;
}

// MuJoCo body of frame f: f's own body when MuJoCo has one of its name, else
// that of the link it hangs from (fixed joints lumped).
int body_of(const model::Model& model, const mjModel* m, int f) {
  for (int g = f; g >= 0; g = model.frame_parent[static_cast<std::size_t>(g)]) {
    const int body =
        mj_name2id(m, mjOBJ_BODY, model.frame_name[static_cast<std::size_t>(g)].c_str());
    if (body >= 0) {
      return g;
    }
  }
  return -1;
}

}  // namespace

std::string visual_mesh_file_name(std::size_t k) {
  return "wbi_render_mesh_" + std::to_string(k) + ".stl";
}

std::vector<VisualMesh> urdf_visual_meshes(const std::string& urdf_file, const fs::path& mesh_dir) {
  const auto urdf = urdf::parseURDFFile(urdf_file);
  if (!urdf) {
    throw std::runtime_error(urdf_file + ": not a URDF that urdfdom reads");
  }
  const fs::path urdf_dir = fs::path(urdf_file).parent_path();
  std::vector<VisualMesh> out;
  for (const auto& [name, link] : urdf->links_) {
    for (const auto& visual : link->visual_array) {
      if (!visual || !visual->geometry || visual->geometry->type != urdf::Geometry::MESH) {
        continue;
      }
      const auto mesh = std::dynamic_pointer_cast<urdf::Mesh>(visual->geometry);
      VisualMesh v;
      v.link = name;
      v.file = resolve(mesh->filename, urdf_dir, mesh_dir);
      std::string extension = v.file.extension().string();
      for (auto& c : extension) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      }
      if (extension != ".stl") {
        throw std::runtime_error("--mesh-path: link " + name + ": " + mesh->filename +
                                 ": MuJoCo 2.2 reads binary STL meshes only here");
      }
      if (!fs::exists(v.file)) {
        throw std::runtime_error("--mesh-path: link " + name + ": " + mesh->filename +
                                 " not found (looked for " + v.file.string() + ")");
      }
      v.scale = {mesh->scale.x, mesh->scale.y, mesh->scale.z};
      const auto& o = visual->origin;
      v.p_LV = {o.position.x, o.position.y, o.position.z};
      double x = 0, y = 0, z = 0, w = 1;
      o.rotation.getQuaternion(x, y, z, w);
      v.q_LV = Quaterniond(w, x, y, z).normalized();
      out.push_back(std::move(v));
    }
  }
  return out;
}

std::string add_visual_meshes(std::string xml, const std::vector<VisualMesh>& meshes,
                              const model::Model& model, const mjModel* plain) {
  std::string assets = "  <asset>\n";
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    const VisualMesh& v = meshes[k];
    const int f = model.frame_id(v.link);
    const int g = body_of(model, plain, f);
    if (g < 0) {
      throw std::logic_error("add_visual_meshes: no MuJoCo body for link " + v.link);
    }
    // Both frames belong to one model body B: X_GV = X_BG⁻¹ X_BF X_FV.
    const auto uf = static_cast<std::size_t>(f);
    const auto ug = static_cast<std::size_t>(g);
    const Matrix3d R_GF = model.frame_R_BF[ug].transpose() * model.frame_R_BF[uf];
    const Vector3d p_GF =
        model.frame_R_BF[ug].transpose() * (model.frame_p_BF[uf] - model.frame_p_BF[ug]);
    const Vector3d p_GV = p_GF + R_GF * v.p_LV;
    const Quaterniond q_GV = Quaterniond(R_GF) * v.q_LV;
    const std::string mesh_name = "wbi_render_mesh_" + std::to_string(k);
    assets += "    <mesh name=\"" + mesh_name + "\" file=\"" + visual_mesh_file_name(k) +
              "\" scale=\"" + numbers({v.scale.x(), v.scale.y(), v.scale.z()}) + "\"/>\n";
    const std::string geom =
        "<geom type=\"mesh\" mesh=\"" + mesh_name + "\" pos=\"" +
        numbers({p_GV.x(), p_GV.y(), p_GV.z()}) + "\" quat=\"" +
        numbers({q_GV.w(), q_GV.x(), q_GV.y(), q_GV.z()}) +
        "\" contype=\"0\" conaffinity=\"0\" group=\"2\" rgba=\"0.75 0.76 0.8 1\"/>\n";
    // After the body's opening tag (the world body's for a fixed root named "world").
    const std::string& body = model.frame_name[ug];
    const bool world = mj_name2id(plain, mjOBJ_BODY, body.c_str()) == 0;
    const std::string open = world ? "<worldbody>" : "<body name=\"" + body + "\"";
    auto at = xml.find(open);
    if (at != std::string::npos) {
      at = xml.find(">\n", at);
    }
    if (at == std::string::npos) {
      throw std::logic_error("add_visual_meshes: body " + body + " not in the MJCF text");
    }
    xml.insert(at + 2, "    " + geom);
  }
  assets += "  </asset>\n";
  const auto world = xml.find("  <worldbody>\n");
  xml.insert(world, assets);
  return xml;
}

}  // namespace wbi::render
