// No heap allocation per call after construction (and one warm-up call):
// counted with a replaced operator new (tests/support/allocation_counter).
// The "wbi" backend allocates nothing. The "dart" backend allocates nothing of
// its own; DART's Skeleton::getMassMatrix allocates two nv-sized vectors per
// update (it saves and restores the accelerations through
// MetaSkeleton::getAccelerations / setAccelerations), which is expected exactly,
// so that any other allocation fails (model_service/README.md).
#include <gtest/gtest.h>

#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "allocation_counter.hpp"
#include "backend_test_common.hpp"

namespace {

namespace wm = wbi::model;

struct Operation {
  std::string name;
  std::function<void()> call;
};

// Allocations of each operation on its second call at a new state.
// With `armature`, every joint gets 0.1 (the backends' armature terms on the path).
void expect_no_allocation(const std::string& backend_name, const std::string& urdf,
                          bool armature = false) {
  wm::LoadOptions options;
  if (armature) {
    for (const std::string& joint : wm::load_urdf_file(urdf).joint_name) {
      options.armature[joint] = 0.1;
    }
  }
  auto backend = wm::make_model_backend(backend_name, urdf, options);
  const wm::Model& model = backend->model();
  std::mt19937 rng(7);
  auto a = wbi::test::random_state(model, rng);
  const auto b = wbi::test::random_state(model, rng);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  std::vector<wm::ExternalWrench> wrenches(1);
  wrenches[0].frame = model.n_frames() - 1;
  wrenches[0].wrench << 1, 2, 3, 0.1, 0.2, 0.3;
  const int frame = model.n_frames() - 1;
  const std::vector<Operation> operations = {
      {"mass_matrix", [&] { backend->mass_matrix(a.q); }},
      {"bias_forces", [&] { backend->bias_forces(a.q, a.nu, g); }},
      {"gravity_forces", [&] { backend->gravity_forces(a.q, g); }},
      {"inverse_dynamics", [&] { backend->inverse_dynamics(a.q, a.nu, a.dnu, g); }},
      {"inverse_dynamics+wrench",
       [&] { backend->inverse_dynamics(a.q, a.nu, a.dnu, g, wrenches); }},
      {"forward_dynamics", [&] { backend->forward_dynamics(a.q, a.nu, a.tau, g); }},
      {"forward_dynamics+wrench",
       [&] { backend->forward_dynamics(a.q, a.nu, a.tau, g, wrenches); }},
      {"frame_pose", [&] { backend->frame_pose(a.q, frame); }},
      {"frame_jacobian", [&] { backend->frame_jacobian(a.q, frame); }},
      {"frame_bias_acceleration", [&] { backend->frame_bias_acceleration(a.q, a.nu, frame); }},
      {"center_of_mass", [&] { backend->center_of_mass(a.q); }},
      {"com_jacobian", [&] { backend->com_jacobian(a.q); }},
      {"centroidal_momentum", [&] { backend->centroidal_momentum(a.q, a.nu); }},
      {"centroidal_momentum_matrix", [&] { backend->centroidal_momentum_matrix(a.q); }},
  };
  for (const auto& operation : operations) {
    operation.call();  // warm-up: first-use caches
  }
  a = b;  // copy assignment of equal sizes: no allocation, a new state
  for (const auto& operation : operations) {
    const long before = wbi::test::allocation_count();
    operation.call();
    const long allocations = wbi::test::allocation_count() - before;
    std::cout << "[ allocs   ] " << backend_name << " " << operation.name << ": " << allocations
              << "\n";
    const long expected = backend_name == "dart" && operation.name == "mass_matrix" ? 2 : 0;
    EXPECT_EQ(allocations, expected) << backend_name << " " << operation.name << " on " << urdf;
  }
}

TEST(NoMalloc, WbiBackend) {
  expect_no_allocation("wbi", wbi::test::project_model("humanoid.urdf").string());
  expect_no_allocation("wbi", wbi::test::project_model("arm7.urdf").string());
  expect_no_allocation("wbi", wbi::test::project_model("humanoid.urdf").string(), true);
}

TEST(NoMalloc, DartBackend) {
  if (!wbi::test::dart_built()) {
    GTEST_SKIP() << wbi::test::kDartMissing;
  }
  expect_no_allocation("dart", wbi::test::project_model("humanoid.urdf").string());
  expect_no_allocation("dart", wbi::test::project_model("arm7.urdf").string());
  expect_no_allocation("dart", wbi::test::project_model("humanoid.urdf").string(), true);
}

}  // namespace
