// How long a model backend's main algorithms take, as `wbi model bench` reports
// it: the median, over batches, of the mean ns per call, the calls cycling
// through random states. A quick figure for any URDF and backend without the
// Google Benchmark suite (bench/model, wbi_bench_model).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <wbi/model/backend.hpp>
#include <wbi/model/model.hpp>

namespace wbi::model_inspect {

struct OperationTiming {
  std::string key;  // e.g. "mass_matrix_ns"
  double median_ns = 0.0;
};

struct TimingReport {
  std::string model;  // Model::name
  std::string file;   // Model::source
  std::string backend;
  int nv = 0;
  int states = 0;              // random states cycled through
  std::string jacobian_frame;  // the frame of jacobian_ns and forward_kinematics_ns
  // In this order: mass_matrix_ns, bias_forces_ns, gravity_forces_ns,
  // inverse_dynamics_ns, forward_dynamics_ns, jacobian_ns, forward_kinematics_ns,
  // centroidal_momentum_matrix_ns.
  std::vector<OperationTiming> timings;
};

// The frame the Jacobian and pose are timed on: the first frame on a deepest
// body (a hand or a foot), so that the figure includes a long support.
int deepest_frame(const model::Model& model);

// Times each operation over `states` random states (fixed seed) in batches of
// `batch` calls; call b of batch s is at state (s + b) mod states, so that
// consecutive calls never repeat a state (a backend that caches on unchanged
// inputs, like DART, is timed computing). Throws std::invalid_argument when
// states or batch is below 1.
TimingReport time_algorithms(model::ModelBackend& backend, int states, int batch);

// {model, file, backend, nv, jacobian_frame, <key>: median ns, ...}
nlohmann::json timing_json(const TimingReport& report);

// One heading line, one line per operation, one line naming the Jacobian frame.
// Leaves `out` in fixed notation with precision 0.
void write_timing_text(std::ostream& out, const TimingReport& report);

}  // namespace wbi::model_inspect
