// Timing of a backend's algorithms (algorithm_timing.hpp).
#include <wbi/model_inspect/algorithm_timing.hpp>

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <random>
#include <stdexcept>

#include <wbi/model/configuration.hpp>

namespace wbi::model_inspect {

namespace {

namespace wm = wbi::model;

// Median over batches of the mean ns per call in a batch of `batch` calls; call b
// of batch s is at state (s + b) mod states.
template <typename Call>
double median_ns(int states, int batch, Call call) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> samples;
  for (int s = 0; s < states; ++s) {
    const auto t0 = Clock::now();
    for (int b = 0; b < batch; ++b) {
      call((s + b) % states);
    }
    const auto t1 = Clock::now();
    samples.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / batch);
  }
  std::nth_element(samples.begin(),
                   samples.begin() + static_cast<std::ptrdiff_t>(samples.size() / 2),
                   samples.end());
  return samples[samples.size() / 2];
}

// Random q, ν, τ and ν̇ (entries in [-1, 1]) for every state, from a fixed seed
// so that two runs time the same states.
struct RandomStates {
  std::vector<Eigen::VectorXd> q, nu, tau, dnu;
};

RandomStates random_states(const wm::Model& m, int states) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  RandomStates out;
  for (int s = 0; s < states; ++s) {
    out.q.push_back(wm::random_configuration(m, rng));
    Eigen::VectorXd v(m.nv), t(m.nv), a(m.nv);
    for (int k = 0; k < m.nv; ++k) {
      v[k] = unit(rng);
      t[k] = unit(rng);
      a[k] = unit(rng);
    }
    out.nu.push_back(v);
    out.tau.push_back(t);
    out.dnu.push_back(a);
  }
  return out;
}

}  // namespace

int deepest_frame(const wm::Model& m) {
  int frame = 0;
  int deepest = -1;
  for (int f = 0; f < m.n_frames(); ++f) {
    int depth = 0;
    for (int i = m.frame_body[static_cast<std::size_t>(f)]; i > 0;
         i = m.parent[static_cast<std::size_t>(i)]) {
      ++depth;
    }
    if (depth > deepest) {
      deepest = depth;
      frame = f;
    }
  }
  return frame;
}

TimingReport time_algorithms(wm::ModelBackend& be, int states, int batch) {
  if (states < 1 || batch < 1) {
    throw std::invalid_argument("time_algorithms: states and batch must be at least 1");
  }
  const wm::Model& m = be.model();
  const RandomStates x = random_states(m, states);
  const int frame = deepest_frame(m);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  auto at = [](int s) { return static_cast<std::size_t>(s); };
  // Every result is added to a volatile so that no call is optimised away.
  volatile double sink = 0.0;
  TimingReport report;
  report.model = m.name;
  report.file = m.source;
  report.backend = std::string(be.name());
  report.nv = m.nv;
  report.states = states;
  report.jacobian_frame = m.frame_name[static_cast<std::size_t>(frame)];
  auto time = [&](const char* key, auto call) {
    report.timings.push_back({key, median_ns(states, batch, call)});
  };
  time("mass_matrix_ns", [&](int s) { sink = sink + be.mass_matrix(x.q[at(s)])(0, 0); });
  time("bias_forces_ns",
       [&](int s) { sink = sink + be.bias_forces(x.q[at(s)], x.nu[at(s)], g)[0]; });
  time("gravity_forces_ns", [&](int s) { sink = sink + be.gravity_forces(x.q[at(s)], g)[0]; });
  time("inverse_dynamics_ns", [&](int s) {
    sink = sink + be.inverse_dynamics(x.q[at(s)], x.nu[at(s)], x.dnu[at(s)], g)[0];
  });
  time("forward_dynamics_ns", [&](int s) {
    sink = sink + be.forward_dynamics(x.q[at(s)], x.nu[at(s)], x.tau[at(s)], g)[0];
  });
  time("jacobian_ns", [&](int s) { sink = sink + be.frame_jacobian(x.q[at(s)], frame)(0, 0); });
  time("forward_kinematics_ns",
       [&](int s) { sink = sink + be.frame_pose(x.q[at(s)], frame)(0, 3); });
  time("centroidal_momentum_matrix_ns",
       [&](int s) { sink = sink + be.centroidal_momentum_matrix(x.q[at(s)])(0, 0); });
  return report;
}

nlohmann::json timing_json(const TimingReport& report) {
  nlohmann::json out;
  out["model"] = report.model;
  out["file"] = report.file;
  out["backend"] = report.backend;
  out["nv"] = report.nv;
  for (const auto& timing : report.timings) {
    out[timing.key] = timing.median_ns;
  }
  out["jacobian_frame"] = report.jacobian_frame;
  return out;
}

void write_timing_text(std::ostream& out, const TimingReport& report) {
  out << "model " << report.model << " (" << report.file << "), nv = " << report.nv << ", backend "
      << report.backend << ", median ns per call over " << report.states << " random states:\n";
  for (const auto& timing : report.timings) {
    out << "  " << std::left << std::setw(32) << timing.key << std::right << std::setw(10)
        << std::fixed << std::setprecision(0) << timing.median_ns << "\n";
  }
  out << "  (jacobian_ns: frame '" << report.jacobian_frame
      << "', including the kinematics of its support)\n";
}

}  // namespace wbi::model_inspect
