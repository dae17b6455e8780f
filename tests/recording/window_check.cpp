// wbi_test_window_check FILE STREAM KIND[,KIND...] BEFORE_S AFTER_S: checks a
// windowed recorder's file (window_file_check.hpp): it holds a trigger event,
// the SensorSample stream STREAM reaches BEFORE_S before the first trigger and
// AFTER_S after the last (to within kEdgeS: the first and last samples lie
// inside the window, at most a pause of the robot's pacing from its edges), and no
// sample of the stream is missing. Prints one line of figures; exit 0 pass,
// 1 fail, 2 usage.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include <wbi/recording/window_recorder.hpp>

#include "window_file_check.hpp"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::cerr << "usage: wbi_test_window_check FILE STREAM KIND[,KIND...] BEFORE_S AFTER_S\n";
    return 2;
  }
  // The window is cut on the wall clock, the stream's samples come at the
  // robot's pace: a real-time simulation that falls behind pauses (up to
  // real_time_max_lag_s, 0.02 s, before it says so), and a pause at the
  // window's edge leaves its first sample that far inside. A CI run met
  // 4.994 s for 5 s (a 6 ms pause, no sample missing by Header.seq); 5 ms
  // was narrower than the pacer's own allowance.
  constexpr double kEdgeS = 0.02;
  const std::string file = argv[1];
  const auto kinds = wbi::recording::parse_trigger_kinds(argv[3]);
  const double before = std::atof(argv[4]);
  const double after = std::atof(argv[5]);
  const auto report = wbi::test::check_window_file(file, argv[2], kinds);
  if (!report.problem.empty()) {
    std::cout << file << ": " << report.problem << "\n";
    return 1;
  }
  std::printf(
      "%s: %zu trigger events (first from %s), %zu events; %s: %zu samples, %.3f s before "
      "the first trigger, %.3f s after the last, %zu gaps (%llu missing)\n",
      file.c_str(), report.trigger_sources.size(), report.trigger_sources.front().c_str(),
      report.events, argv[2], report.stream.size(), report.before_s, report.after_s, report.gaps,
      static_cast<unsigned long long>(report.missing));
  for (const auto& [topic, missing] : report.missing_by_topic) {
    std::printf("  %s: %llu missing\n", topic.c_str(), static_cast<unsigned long long>(missing));
  }
  const bool pass =
      report.before_s >= before - kEdgeS && report.after_s >= after - kEdgeS && report.gaps == 0;
  return pass ? 0 : 1;
}
