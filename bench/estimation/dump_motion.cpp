// Writes the estimator benchmark's humanoid motion as CSV, for `wbi estimate`
// and for plotting: PREFIX_encoder.csv (t, the quantised positions, the input
// format of `wbi estimate`) and PREFIX_truth.csv (t, q, dq, ddq of every joint).
// Usage: wbi_bench_estimation_dump PREFIX [--no-friction]
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "motion.hpp"
#include "simulated_motion.hpp"
#include "wbi/sim/sim_backend.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: wbi_bench_estimation_dump PREFIX [--no-friction]\n";
    return 1;
  }
  const std::string prefix = argv[1];
  const bool friction = !(argc > 2 && std::string(argv[2]) == "--no-friction");
  const std::string urdf = WBI_PROJECT_MODELS_DIR "/humanoid.urdf";
  wbi::robot_config::RobotConfig config;
  config.urdf = urdf;
  config.fixed_base = true;
  wbi::sim::SimBackend sim(config);
  sim.configure();
  const auto& names = sim.description().joint_names;
  const auto motion =
      wbi::bench::simulate_humanoid_motion(urdf, wbi::bench::kHumanoidDurationS, friction);
  const auto recording = wbi::bench::record(motion, wbi::bench::kRateHz,
                                            wbi::bench::kHumanoidDurationS, wbi::bench::kCounts);
  std::ofstream encoder(prefix + "_encoder.csv");
  std::ofstream truth(prefix + "_truth.csv");
  encoder.precision(17);
  truth.precision(17);
  encoder << "t";
  truth << "t";
  for (const auto& kind : {"q_", "dq_", "ddq_"}) {
    for (const auto& name : names) {
      truth << "," << kind << name;
    }
  }
  for (const auto& name : names) {
    encoder << "," << name;
  }
  encoder << "\n";
  truth << "\n";
  for (Eigen::Index k = 0; k < recording.q_measured.cols(); ++k) {
    const double t = 1e-9 * static_cast<double>(recording.stamp_ns[static_cast<std::size_t>(k)]);
    encoder << t;
    truth << t;
    for (Eigen::Index j = 0; j < recording.q_measured.rows(); ++j) {
      encoder << "," << recording.q_measured(j, k);
    }
    for (const auto* m : {&recording.q_true, &recording.dq_true, &recording.ddq_true}) {
      for (Eigen::Index j = 0; j < m->rows(); ++j) {
        truth << "," << (*m)(j, k);
      }
    }
    encoder << "\n";
    truth << "\n";
  }
  return 0;
}
