// What loading plugins adds to a process's start (issue 53's target: ≤ 50 ms
// for the plugins a deploy file names). Each benchmark starts wbi_host and
// waits for it to end:
//   BM_StartNoPlugin      `wbi_host --no-such-flag`: the program and its
//                         libraries loaded, the arguments refused before any plugin
//   BM_StartBuiltin       `wbi_host --help`: the built-in plugin loaded and listed
//   BM_StartLabPlugin     `wbi_host --help --plugin <a lab's plugin>`: one more
// Counter plugin_ms (mean wall time less BM_StartNoPlugin's, per run).
//   build/bin/wbi_bench_plugins --benchmark_format=json
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace {

const std::string kHost = std::string(WBI_BINARY_DIR) + "/bin/wbi_host";
const std::string kLabPlugin = WBI_LAB_PLUGIN;

// Starts the program with its output to /dev/null and waits for its end: seconds.
double run(const std::vector<std::string>& args) {
  std::vector<char*> argv{const_cast<char*>(kHost.c_str())};
  for (const auto& arg : args) {
    argv.push_back(const_cast<char*>(arg.c_str()));
  }
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = -1;
  const int failed = posix_spawn(&pid, kHost.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (failed != 0) {
    return -1.0;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double baseline_s = 0.0;

void time_start(benchmark::State& state, const std::vector<std::string>& args, bool baseline) {
  double total = 0.0;
  for (auto _ : state) {
    const double seconds = run(args);
    if (seconds < 0.0) {
      state.SkipWithError(("cannot start " + kHost).c_str());
      return;
    }
    state.SetIterationTime(seconds);
    total += seconds;
  }
  const double mean = total / static_cast<double>(state.iterations());
  if (baseline) {
    baseline_s = mean;
  }
  state.counters["plugin_ms"] = 1e3 * (mean - baseline_s);
}

void BM_StartNoPlugin(benchmark::State& state) { time_start(state, {"--no-such-flag"}, true); }
void BM_StartBuiltin(benchmark::State& state) { time_start(state, {"--help"}, false); }
void BM_StartLabPlugin(benchmark::State& state) {
  time_start(state, {"--help", "--plugin", kLabPlugin}, false);
}

BENCHMARK(BM_StartNoPlugin)->UseManualTime()->Iterations(30)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StartBuiltin)->UseManualTime()->Iterations(30)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StartLabPlugin)->UseManualTime()->Iterations(30)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
