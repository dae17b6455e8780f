// Argument checks shared by the backends (no allocation unless they throw).
#pragma once

#include <stdexcept>
#include <string>

#include <Eigen/Core>

#include "wbi/model/model.hpp"

namespace wbi::model::backend_detail {

inline void check_frame(const Model& model, int frame) {
  if (frame < 0 || frame >= model.n_frames()) {
    throw std::invalid_argument("frame index " + std::to_string(frame) + " out of range [0, " +
                                std::to_string(model.n_frames()) + ") of model '" + model.name +
                                "'");
  }
}

inline void check_size(const char* what, Eigen::Index got, int expected) {
  if (got != expected) {
    throw std::invalid_argument(std::string(what) + " has size " + std::to_string(got) +
                                ", expected " + std::to_string(expected));
  }
}

}  // namespace wbi::model::backend_detail
