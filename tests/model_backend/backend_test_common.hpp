// Helpers of the backend tests: whether DART is built, a random state.
#pragma once

#include <algorithm>
#include <random>
#include <string>

#include "model_test_common.hpp"
#include "wbi/model/backend.hpp"

namespace wbi::test {

inline bool dart_built() {
  const auto names = wbi::model::model_backend_names();
  return std::find(names.begin(), names.end(), "dart") != names.end();
}

inline constexpr const char* kDartMissing = "wbi was built without DART (WBI_WITH_DART OFF)";

struct RandomState {
  Eigen::VectorXd q, nu, dnu, tau;
};

inline RandomState random_state(const wbi::model::Model& model, std::mt19937& rng) {
  RandomState s;
  s.q = wbi::model::random_configuration(model, rng);
  s.nu = random_vector(model.nv, rng, 2.0);
  s.dnu = random_vector(model.nv, rng, 3.0);
  s.tau = random_vector(model.nv, rng, 10.0);
  return s;
}

}  // namespace wbi::test
