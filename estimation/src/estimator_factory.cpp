#include "wbi/estimation/estimator_factory.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "wbi/estimation/adaptive_window.hpp"
#include "wbi/estimation/backward_difference.hpp"
#include "wbi/estimation/kalman_derivative.hpp"
#include "wbi/estimation/split_kalman.hpp"

namespace wbi::estimation {
namespace {

std::vector<ParameterSpec> with_stream_parameters(std::vector<ParameterSpec> specs) {
  const StreamParameters stream;
  specs.push_back({"sample-rate", "HZ", stream.sample_rate_hz, 1e-3, 1e7, false,
                   "nominal sample rate, Hz: counts dropped samples and tunes the filter"});
  specs.push_back({"max-gap", "S", stream.max_gap_s, 0.0, 1e9, false,
                   "a longer interval between stamps restarts the estimator, s"});
  return specs;
}

std::vector<MethodInfo> build_methods() {
  const KalmanParameters kalman;
  const SplitKalmanParameters split;
  const AdaptiveWindowParameters window;
  const BackwardDifferenceParameters difference;
  return {
      {"split-kalman",
       "a Kalman filter for the velocity (loop-safe) and, for the acceleration, a bank of "
       "Kalman filters from quiet to agile blended per joint by the likelihood of their "
       "innovations, with a second bank that anticipates friction sticks at velocity reversals; "
       "gains from the encoder resolution, the sample rate and the process noises",
       with_stream_parameters({
           {"resolution", "COUNTS", split.resolution_counts, 2, 1e12, false,
            "encoder counts per revolution (quantisation noise)"},
           {"velocity-order", "M", static_cast<double>(split.velocity_order), 2, 4, true,
            "model order of the velocity filter: 2 constant acceleration, 3 constant jerk, 4 "
            "constant snap"},
           {"velocity-process-noise", "SIGMA", split.velocity_process_noise, 1e-12, 1e15, false,
            "process noise of the velocity filter, rad/s^(M+1)/sqrt(Hz)"},
           {"velocity-cutoff", "HZ", split.velocity_cutoff_hz, 0, 1e9, false,
            "first-order low-pass on the velocity, Hz; 0: none"},
           {"acceleration-order", "M", static_cast<double>(split.acceleration_order), 2, 4, true,
            "model order of the acceleration filters"},
           {"acceleration-noise-min", "SIGMA", split.acceleration_noise_min, 1e-12, 1e15, false,
            "process noise of the quietest acceleration filter, rad/s^(M+1)/sqrt(Hz)"},
           {"acceleration-noise-max", "SIGMA", split.acceleration_noise_max, 1e-12, 1e15, false,
            "process noise of the most agile acceleration filter (>= the minimum)"},
           {"acceleration-models", "N", static_cast<double>(split.acceleration_models), 1, 8, true,
            "acceleration filters, process noises spaced geometrically from min to max"},
           {"acceleration-memory", "S", split.acceleration_memory_s, 1e-4, 1e3, false,
            "forgetting time of the likelihoods that blend the acceleration filters, s"},
           {"stick-duration", "S", split.stick_duration_s, 0, 1, false,
            "stick assumed at each velocity reversal (Coulomb friction) by a second "
            "acceleration bank, s; 0: no stick anticipation"},
           {"stick-fraction", "F", split.stick_fraction, 0, 1, false,
            "fraction of the acceleration kept during an assumed stick"},
           {"stick-release", "S", split.stick_release_s, 0, 1, false,
            "time constant of the acceleration's return after an assumed stick, s; 0: at once"},
           {"stick-velocity", "RAD/S", split.stick_velocity, 0, 1e3, false,
            "a joint slowing down below this speed is taken to reverse; 0: at the sign change "
            "only"},
           {"stick-memory", "S", split.stick_memory_s, 1e-3, 1e3, false,
            "forgetting time of the likelihoods that blend the sticking and non-sticking banks, s"},
       })},
      {"kalman",
       "Kalman filter on a constant-jerk model (by default), its gain computed from the "
       "encoder resolution, the sample rate and the process noise",
       with_stream_parameters({
           {"model-order", "M", static_cast<double>(kalman.model_order), 2, 4, true,
            "model order: 2 constant acceleration, 3 constant jerk, 4 constant snap"},
           {"resolution", "COUNTS", kalman.resolution_counts, 2, 1e12, false,
            "encoder counts per revolution (quantisation noise)"},
           {"process-noise", "SIGMA", kalman.process_noise, 1e-12, 1e15, false,
            "density of the white noise driving the highest derivative, rad/s^(M+1)/sqrt(Hz)"},
       })},
      {"adaptive-window",
       "least-squares fits over an adaptive window (Janabi-Sharifi, Hayward and Chen 2000)",
       with_stream_parameters({
           {"velocity-window", "N", static_cast<double>(window.velocity_window), 2, 1000, true,
            "longest window of the linear fit for velocity, samples"},
           {"acceleration-window", "N", static_cast<double>(window.acceleration_window), 3, 1000,
            true, "longest window of the quadratic fit for acceleration, samples"},
           {"threshold", "D", window.threshold_rad, 1e-12, 1e6, false,
            "largest distance of a sample from the fit, rad"},
       })},
      {"backward-difference", "backward differences with an optional first-order low-pass",
       with_stream_parameters({
           {"cutoff", "HZ", difference.cutoff_hz, 0, 1e9, false,
            "low-pass cut-off frequency, Hz; 0: no low-pass"},
       })},
  };
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& name : names) {
    out += (out.empty() ? "" : " ") + name;
  }
  return out;
}

std::string format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// The value of every parameter of `info`: defaults overridden by `given`, validated.
Parameters resolve(const MethodInfo& info, const Parameters& given) {
  Parameters values;
  for (const auto& spec : info.parameters) {
    values[spec.name] = spec.default_value;
  }
  for (const auto& [name, value] : given) {
    const auto it = values.find(name);
    if (it == values.end()) {
      std::vector<std::string> known;
      for (const auto& spec : info.parameters) {
        known.push_back(spec.name);
      }
      throw std::invalid_argument("method '" + info.name + "' has no parameter '" + name +
                                  "' (its parameters: " + join_names(known) + ")");
    }
    it->second = value;
  }
  for (const auto& spec : info.parameters) {
    const double value = values[spec.name];
    const bool in_range = std::isfinite(value) && value >= spec.min && value <= spec.max;
    if (!in_range || (spec.integer && value != std::round(value))) {
      throw std::invalid_argument("method '" + info.name + "': parameter '" + spec.name +
                                  "' must be " + (spec.integer ? "an integer" : "a number") +
                                  " in [" + format(spec.min) + ", " + format(spec.max) + "], got " +
                                  format(value));
    }
  }
  return values;
}

}  // namespace

const std::vector<MethodInfo>& methods() {
  static const std::vector<MethodInfo> all = build_methods();
  return all;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const auto& info : methods()) {
    names.push_back(info.name);
  }
  return names;
}

const MethodInfo& method_info(const std::string& name) {
  for (const auto& info : methods()) {
    if (info.name == name) {
      return info;
    }
  }
  throw std::invalid_argument("unknown estimation method '" + name +
                              "' (known: " + join_names(method_names()) + ")");
}

std::unique_ptr<DerivativeEstimator> make_estimator(const std::string& method, Eigen::Index joints,
                                                    const Parameters& given) {
  const MethodInfo& info = method_info(method);
  const Parameters p = resolve(info, given);
  const StreamParameters stream{p.at("sample-rate"), p.at("max-gap")};
  if (method == "split-kalman") {
    const SplitKalmanParameters params{p.at("resolution"),
                                       static_cast<int>(p.at("velocity-order")),
                                       p.at("velocity-process-noise"),
                                       p.at("velocity-cutoff"),
                                       static_cast<int>(p.at("acceleration-order")),
                                       p.at("acceleration-noise-min"),
                                       p.at("acceleration-noise-max"),
                                       static_cast<int>(p.at("acceleration-models")),
                                       p.at("acceleration-memory"),
                                       p.at("stick-duration"),
                                       p.at("stick-fraction"),
                                       p.at("stick-release"),
                                       p.at("stick-velocity"),
                                       p.at("stick-memory")};
    return std::make_unique<SplitKalmanEstimator>(joints, params, stream);
  }
  if (method == "kalman") {
    const KalmanParameters params{static_cast<int>(p.at("model-order")), p.at("resolution"),
                                  p.at("process-noise")};
    return std::make_unique<KalmanEstimator>(joints, params, stream);
  }
  if (method == "adaptive-window") {
    const AdaptiveWindowParameters params{static_cast<int>(p.at("velocity-window")),
                                          static_cast<int>(p.at("acceleration-window")),
                                          p.at("threshold")};
    return std::make_unique<AdaptiveWindowEstimator>(joints, params, stream);
  }
  const BackwardDifferenceParameters params{p.at("cutoff")};
  return std::make_unique<BackwardDifferenceEstimator>(joints, params, stream);
}

}  // namespace wbi::estimation
