// Accuracy and cost of the joint velocity/acceleration estimators.
//
// Accuracy/<motion>/<method>: the whole recording (1 kHz, 14-bit encoders)
// through the estimator; counters rmse_dq (rad/s), rmse_ddq (rad/s²) over all
// joints after a 0.5 s warm-up, lag_dq_ms and lag_ddq_ms (the delay that
// minimises the RMSE), rmse_ddq_away (rmse_ddq without the samples from 5 ms
// before to 50 ms after each velocity reversal of a joint, where friction
// makes the true ddq jump), us_per_sample (time per joint-vector sample).
// Accuracy/<motion>/truth-blind-<N>ms (motions with friction): the truth,
// blind for N ms after every jump of the true ddq: a lower bound for
// estimators that must see a jump in the positions before following it.
// Cost/<method>: one update of 32 joints per iteration.
// Run with --benchmark_format=json for JSON.
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "accuracy.hpp"
#include "motion.hpp"
#include "simulated_motion.hpp"
#include "wbi/estimation/estimator_factory.hpp"

namespace wbi::bench {
namespace {

constexpr double kWarmUpS = 0.5;
// Around each velocity reversal: the friction notch and the estimators' recovery.
constexpr double kReversalBeforeS = 0.005;
constexpr double kReversalAfterS = 0.05;
// A jump of the true ddq between two samples (a jerk of 10^4 rad/s³, ten
// times the fastest commanded one): only friction makes such jumps.
constexpr double kJumpRadPerS2 = 10.0;

struct Configuration {
  std::string label;
  std::string method;
  estimation::Parameters parameters;
};

// Every method: the original whole-body interface's adaptive window, the
// backward-difference baselines and the recommended Kalman filter.
const std::vector<Configuration>& configurations() {
  static const std::vector<Configuration> all = {
      {"adaptive-window", "adaptive-window", {}},
      {"backward-difference", "backward-difference", {}},
      {"backward-difference-lp50", "backward-difference", {{"cutoff", 50.0}}},
      {"kalman", "kalman", {}},
      {"kalman-agile", "kalman", {{"process-noise", 3000.0}}},
      {"kalman-order2", "kalman", {{"model-order", 2.0}, {"process-noise", 30.0}}},
      {"split-kalman", "split-kalman", {}},
      {"split-kalman-no-stick", "split-kalman", {{"stick-duration", 0.0}}},
      {"split-kalman-loop-lp30",
       "split-kalman",
       {{"velocity-order", 2.0}, {"velocity-process-noise", 3000.0}, {"velocity-cutoff", 30.0}}},
      {"split-kalman-loop-lp50",
       "split-kalman",
       {{"velocity-order", 2.0}, {"velocity-process-noise", 3000.0}, {"velocity-cutoff", 50.0}}},
  };
  return all;
}

struct Scenario {
  std::shared_ptr<const Motion> motion;
  double duration_s;
  double drop_probability;
  std::string label;
  bool friction = false;  // the truth has acceleration jumps (Coulomb friction)
};

const std::vector<Scenario>& scenarios() {
  // Amplitudes keep the peak velocity between 1.6 and 3.1 rad/s, as for
  // humanoid joints; 8 joints with spread phases average the quantisation.
  const auto sine = [](double hz, double amplitude) {
    return std::make_shared<AnalyticMotion>(sinusoid_motion(hz, amplitude, 8));
  };
  static const std::shared_ptr<const Motion> humanoid = std::make_shared<SampledMotion>(
      simulate_humanoid_motion(WBI_PROJECT_MODELS_DIR "/humanoid.urdf", kHumanoidDurationS));
  static const std::shared_ptr<const Motion> frictionless = std::make_shared<SampledMotion>(
      simulate_humanoid_motion(WBI_PROJECT_MODELS_DIR "/humanoid.urdf", kHumanoidDurationS, false));
  static const std::vector<Scenario> all = {
      {sine(0.5, 0.5), 5.0, 0.0, "sine_0.5Hz"},
      {sine(1.0, 0.4), 5.0, 0.0, "sine_1Hz"},
      {sine(2.0, 0.2), 5.0, 0.0, "sine_2Hz"},
      {sine(5.0, 0.1), 5.0, 0.0, "sine_5Hz"},
      {humanoid, kHumanoidDurationS, 0.0, "humanoid_sim", true},
      {humanoid, kHumanoidDurationS, 0.01, "humanoid_sim_1pc_dropped", true},
      {frictionless, kHumanoidDurationS, 0.0, "humanoid_sim_no_friction"},
  };
  return all;
}

EncoderRecording record_scenario(const Scenario& scenario) {
  return record(*scenario.motion, kRateHz, scenario.duration_s, kCounts, scenario.drop_probability);
}

void report_accuracy(benchmark::State& state, const Scenario& scenario,
                     const EncoderRecording& recording, const Estimates& estimates) {
  const Fit dq =
      accuracy(*scenario.motion, recording, estimates.dq, Derivative::velocity, kWarmUpS);
  const Fit ddq =
      accuracy(*scenario.motion, recording, estimates.ddq, Derivative::acceleration, kWarmUpS);
  const SampleMask reversals =
      near_velocity_reversals(recording, kReversalBeforeS, kReversalAfterS);
  state.counters["rmse_dq"] = dq.rmse;
  state.counters["rmse_ddq"] = ddq.rmse;
  state.counters["lag_dq_ms"] = 1e3 * dq.lag_s;
  state.counters["lag_ddq_ms"] = 1e3 * ddq.lag_s;
  state.counters["rmse_ddq_away"] =
      rmse_outside(recording, estimates.ddq, recording.ddq_true, reversals, kWarmUpS);
  state.counters["joints"] = scenario.motion->joints();
}

void accuracy(benchmark::State& state, const Scenario& scenario,
              const Configuration& configuration) {
  const EncoderRecording recording = record_scenario(scenario);
  const auto estimator = estimation::make_estimator(configuration.method, scenario.motion->joints(),
                                                    configuration.parameters);
  Estimates estimates;
  for (auto _ : state) {
    run_estimator(*estimator, recording, estimates);
    benchmark::DoNotOptimize(estimates.dq.data());
  }
  report_accuracy(state, scenario, recording, estimates);
  state.counters["us_per_sample"] = benchmark::Counter(
      1e-6 * static_cast<double>(recording.stamp_ns.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void truth_blind(benchmark::State& state, const Scenario& scenario, int blind_ms) {
  const EncoderRecording recording = record_scenario(scenario);
  Estimates estimates;
  for (auto _ : state) {
    const int blind_samples = static_cast<int>(std::lround(1e-3 * blind_ms * kRateHz));
    estimates = truth_blind_to_jumps(recording, kJumpRadPerS2, blind_samples);
    benchmark::DoNotOptimize(estimates.ddq.data());
  }
  report_accuracy(state, scenario, recording, estimates);
}

void cost(benchmark::State& state, const Configuration& configuration) {
  constexpr Eigen::Index kJoints = 32;
  const EncoderRecording recording =
      record(sinusoid_motion(1.0, 0.4, static_cast<int>(kJoints)), kRateHz, 2.0, kCounts);
  const auto estimator =
      estimation::make_estimator(configuration.method, kJoints, configuration.parameters);
  const auto samples = static_cast<std::int64_t>(recording.stamp_ns.size());
  std::int64_t k = 0;
  std::int64_t stamp = 0;
  for (auto _ : state) {
    // Replays the recording with ever-increasing stamps.
    estimator->update(stamp, recording.q_measured.col(k));
    benchmark::DoNotOptimize(estimator->velocity().data());
    stamp += 1'000'000;
    k = (k + 1) % samples;
  }
  state.counters["joints"] = static_cast<double>(kJoints);
}

int register_all() {
  for (const auto& scenario : scenarios()) {
    for (const auto& configuration : configurations()) {
      benchmark::RegisterBenchmark(
          ("Accuracy/" + scenario.label + "/" + configuration.label).c_str(),
          [&](benchmark::State& state) { accuracy(state, scenario, configuration); })
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    }
    for (const int blind_ms : {3, 5}) {
      if (scenario.friction) {
        benchmark::RegisterBenchmark(
            ("Accuracy/" + scenario.label + "/truth-blind-" + std::to_string(blind_ms) + "ms")
                .c_str(),
            [&, blind_ms](benchmark::State& state) { truth_blind(state, scenario, blind_ms); })
            ->Iterations(1)
            ->Unit(benchmark::kMillisecond);
      }
    }
  }
  for (const auto& configuration : configurations()) {
    benchmark::RegisterBenchmark(("Cost/" + configuration.label).c_str(),
                                 [&](benchmark::State& state) { cost(state, configuration); })
        ->Unit(benchmark::kMicrosecond);
  }
  return 0;
}

const int registered = register_all();

}  // namespace
}  // namespace wbi::bench

BENCHMARK_MAIN();
