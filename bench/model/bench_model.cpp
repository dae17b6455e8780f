// Benchmarks of the model library: ns per call of each algorithm at random
// states, on iCub 3 (../shared/models/iCubGenova09, free-floating, 38 velocities)
// and on models/humanoid.urdf; M, RNEA and ABA also on iCub 3 with armature;
// every algorithm also on TALOS (../shared/models/talos/talos_reduced.urdf, 38 velocities).
// Every call includes its own forward kinematics;
// FrameJacobian includes the kinematics of the frame's support only, and
// FrameJacobianAfterKinematics times the Jacobian alone after a full FK.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "wbi/model/algorithms.hpp"

namespace wm = wbi::model;

namespace {

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);
constexpr int kStates = 64;

struct Fixture {
  wm::Model model;
  std::unique_ptr<wm::Data> data;
  std::vector<Eigen::VectorXd> q, nu, tau;
  int frame = 0;  // a hand or the last frame
};

std::filesystem::path source_dir() { return std::filesystem::path(WBI_SOURCE_DIR); }

// "icub3", "talos", "humanoid", or "icub3_armature": iCub 3 with an armature of 0.05 on
// every joint.
const Fixture* fixture(const std::string& which) {
  static std::unique_ptr<Fixture> icub, icub_armature, talos, humanoid;
  std::unique_ptr<Fixture>& f = which == "icub3"            ? icub
                                : which == "icub3_armature" ? icub_armature
                                : which == "talos"          ? talos
                                                            : humanoid;
  if (!f) {
    const auto models = source_dir().parent_path() / "shared/models";
    const auto path = which.starts_with("icub3") ? models / "iCubGenova09/model.urdf"
                      : which == "talos"         ? models / "talos/talos_reduced.urdf"
                                                 : source_dir() / "models/humanoid.urdf";
    if (!std::filesystem::exists(path)) {
      return nullptr;
    }
    f = std::make_unique<Fixture>();
    wm::LoadOptions options;
    if (which == "icub3_armature") {
      for (const std::string& joint : wm::load_urdf_file(path.string()).joint_name) {
        options.armature[joint] = 0.05;
      }
    }
    f->model = wm::load_urdf_file(path.string(), options);
    f->data = std::make_unique<wm::Data>(f->model);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    for (int i = 0; i < kStates; ++i) {
      f->q.push_back(wm::random_configuration(f->model, rng));
      Eigen::VectorXd v(f->model.nv), t(f->model.nv);
      for (int k = 0; k < f->model.nv; ++k) {
        v[k] = d(rng);
        t[k] = d(rng);
      }
      f->nu.push_back(v);
      f->tau.push_back(t);
    }
    int deepest = -1;  // default: the first frame on a deepest body
    for (int fr = 0; fr < f->model.n_frames(); ++fr) {
      int depth = 0;
      for (int b = f->model.frame_body[static_cast<std::size_t>(fr)]; b > 0;
           b = f->model.parent[static_cast<std::size_t>(b)]) {
        ++depth;
      }
      if (depth > deepest) {
        deepest = depth;
        f->frame = fr;
      }
    }
    for (const char* name : {"r_hand", "r_hand_palm", "r_wrist_1"}) {
      if (f->model.has_frame(name)) {
        f->frame = f->model.frame_id(name);
        break;
      }
    }
  }
  return f.get();
}

template <typename Call>
void run(benchmark::State& state, const std::string& which, Call call) {
  const Fixture* f = fixture(which);
  if (f == nullptr) {
    state.SkipWithError("model not found");
    return;
  }
  wm::Data& data = *f->data;
  std::size_t i = 0;
  for (auto _ : state) {
    call(*f, data, i);
    benchmark::ClobberMemory();
    i = (i + 1) % kStates;
  }
}

void BM_MassMatrix(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(wm::mass_matrix(f.model, d, f.q[i]).data());
  });
}
void BM_BiasForces(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(wm::bias_forces(f.model, d, f.q[i], f.nu[i], kGravity).data());
  });
}
void BM_GravityForces(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(wm::gravity_forces(f.model, d, f.q[i], kGravity).data());
  });
}
void BM_ForwardDynamics(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(
        wm::forward_dynamics(f.model, d, f.q[i], f.nu[i], f.tau[i], kGravity).data());
  });
}
void BM_InverseDynamics(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(
        wm::inverse_dynamics(f.model, d, f.q[i], f.nu[i], f.tau[i], kGravity).data());
  });
}
void BM_ForwardKinematics(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    wm::forward_kinematics(f.model, d, f.q[i]);
    benchmark::DoNotOptimize(d.p_WB.back().data());
  });
}
void BM_FrameJacobian(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(wm::frame_jacobian(f.model, d, f.q[i], f.frame).data());
  });
}
void BM_FrameJacobianAfterKinematics(benchmark::State& s, const std::string& m) {
  const Fixture* f = fixture(m);
  if (f != nullptr) {
    wm::forward_kinematics(f->model, *f->data, f->q[0]);
  }
  run(s, m, [](const Fixture& fx, wm::Data& d, std::size_t) {
    benchmark::DoNotOptimize(wm::frame_jacobian(fx.model, d, fx.frame).data());
  });
}
void BM_FrameBiasAcceleration(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    wm::forward_velocity_kinematics(f.model, d, f.q[i], f.nu[i]);
    benchmark::DoNotOptimize(wm::frame_bias_acceleration(f.model, d, f.frame).data());
  });
}
void BM_CentroidalMomentumMatrix(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(wm::centroidal_momentum_matrix(f.model, d, f.q[i]).data());
  });
}
void BM_CentroidalMomentum(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(wm::centroidal_momentum(f.model, d, f.q[i], f.nu[i]).data());
  });
}
void BM_ComJacobian(benchmark::State& s, const std::string& m) {
  run(s, m, [](const Fixture& f, wm::Data& d, std::size_t i) {
    benchmark::DoNotOptimize(wm::com_jacobian(f.model, d, f.q[i]).data());
  });
}

}  // namespace

#define WBI_BENCH_ALL(model)                                         \
  BENCHMARK_CAPTURE(BM_MassMatrix, model, #model);                   \
  BENCHMARK_CAPTURE(BM_BiasForces, model, #model);                   \
  BENCHMARK_CAPTURE(BM_GravityForces, model, #model);                \
  BENCHMARK_CAPTURE(BM_ForwardDynamics, model, #model);              \
  BENCHMARK_CAPTURE(BM_InverseDynamics, model, #model);              \
  BENCHMARK_CAPTURE(BM_ForwardKinematics, model, #model);            \
  BENCHMARK_CAPTURE(BM_FrameJacobian, model, #model);                \
  BENCHMARK_CAPTURE(BM_FrameJacobianAfterKinematics, model, #model); \
  BENCHMARK_CAPTURE(BM_FrameBiasAcceleration, model, #model);        \
  BENCHMARK_CAPTURE(BM_CentroidalMomentumMatrix, model, #model);     \
  BENCHMARK_CAPTURE(BM_CentroidalMomentum, model, #model);           \
  BENCHMARK_CAPTURE(BM_ComJacobian, model, #model)

WBI_BENCH_ALL(icub3);
WBI_BENCH_ALL(humanoid);
WBI_BENCH_ALL(talos);
// Armature enters these three (and no other algorithm).
BENCHMARK_CAPTURE(BM_MassMatrix, icub3_armature, "icub3_armature");
BENCHMARK_CAPTURE(BM_InverseDynamics, icub3_armature, "icub3_armature");
BENCHMARK_CAPTURE(BM_ForwardDynamics, icub3_armature, "icub3_armature");

BENCHMARK_MAIN();
