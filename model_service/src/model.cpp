#include "wbi/model/model.hpp"

#include <stdexcept>

#include "checks.hpp"

namespace wbi::model {

namespace {
int find(const std::vector<std::string>& names, const std::string& name) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) {
      return static_cast<int>(i);
    }
  }
  return -1;
}
}  // namespace

int Model::joint_id(const std::string& joint) const {
  const int id = find(joint_name, joint);
  if (id < 0) {
    throw std::invalid_argument("model '" + name + "': unknown joint '" + joint + "'");
  }
  return id;
}

int Model::frame_id(const std::string& frame) const {
  const int id = find(frame_name, frame);
  if (id < 0) {
    throw std::invalid_argument("model '" + name + "': unknown frame '" + frame + "'");
  }
  return id;
}

int Model::body_id(const std::string& body) const {
  const int id = find(body_name, body);
  if (id < 0) {
    throw std::invalid_argument("model '" + name + "': unknown body '" + body + "'");
  }
  return id;
}

bool Model::has_joint(const std::string& joint) const { return find(joint_name, joint) >= 0; }
bool Model::has_frame(const std::string& frame) const { return find(frame_name, frame) >= 0; }

namespace detail {

void throw_size(const char* function, const char* argument, long expected, long got) {
  throw std::invalid_argument(std::string(function) + ": argument '" + argument + "' has size " +
                              std::to_string(got) + ", expected " + std::to_string(expected));
}

void throw_frame(const Model& model, int frame) {
  throw std::invalid_argument("model '" + model.name + "': frame index " + std::to_string(frame) +
                              " out of range [0, " + std::to_string(model.n_frames()) + ")");
}

void throw_data(const Model& model) {
  throw std::invalid_argument("model '" + model.name + "': the Data was built for another model");
}

void throw_singular(const Model& model, int body) {
  throw std::runtime_error(
      "forward_dynamics: joint '" + model.joint_name[model.body_joint[body]] + "' of model '" +
      model.name + "' moves a subtree with no inertia about its axis (singular mass matrix)");
}

}  // namespace detail

}  // namespace wbi::model
