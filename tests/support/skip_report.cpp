// Linked into every wbi_add_test: when a test program ran nothing, that is
// when every test it ran was skipped and none failed, it ends with one line
//   skipped: <the first test's reason> (all N tests skipped)
// which ctest's SKIP_REGULAR_EXPRESSION (cmake/WbiTargets.cmake) turns into
// "Skipped". A program of which only some tests skipped stays "Passed" (or
// "Failed"): its other tests ran; scripts/test lists its skipped tests from
// GoogleTest's summary. GTEST_SKIP() messages must therefore not begin a line
// with "skipped: " themselves (tests/README.md, "Skipped tests").
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace {

// The message of the first skipped test, "" if none gave one.
std::string first_skip_message(const testing::UnitTest& unit_test) {
  for (int s = 0; s < unit_test.total_test_suite_count(); ++s) {
    const testing::TestSuite& suite = *unit_test.GetTestSuite(s);
    for (int t = 0; t < suite.total_test_count(); ++t) {
      const testing::TestResult& result = *suite.GetTestInfo(t)->result();
      if (!result.Skipped()) {
        continue;
      }
      for (int p = 0; p < result.total_part_count(); ++p) {
        const testing::TestPartResult& part = result.GetTestPartResult(p);
        if (part.skipped()) {
          std::string message = part.message();
          const auto end = message.find('\n');
          return end == std::string::npos ? message : message.substr(0, end);
        }
      }
      return "";
    }
  }
  return "";
}

class SkipReport : public testing::EmptyTestEventListener {
  void OnTestProgramEnd(const testing::UnitTest& unit_test) override {
    const int ran = unit_test.test_to_run_count();
    if (ran == 0 || unit_test.skipped_test_count() != ran || !unit_test.Passed() ||
        unit_test.ad_hoc_test_result().Failed()) {
      return;
    }
    std::string reason = first_skip_message(unit_test);
    if (reason.empty()) {
      reason = "GTEST_SKIP() without a message";
    }
    std::printf("skipped: %s (all %d test%s skipped)\n", reason.c_str(), ran, ran == 1 ? "" : "s");
    std::fflush(stdout);
  }
};

struct InstallSkipReport {
  InstallSkipReport() { testing::UnitTest::GetInstance()->listeners().Append(new SkipReport); }
};
const InstallSkipReport install_skip_report;

}  // namespace
