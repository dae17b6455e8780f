// idl/run_fastddsgen.cmake, as the build runs it for every .idl file: silent
// when fastddsgen succeeds (no banner, no per-file progress), its error lines
// (without colour codes) and a failure when it does not, also when it prints
// an error but exits 0; only the file's own generated code lands in OUT_DIR.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "child_process.hpp"
#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;

struct Outcome {
  int code;
  std::string output;
};

class FastddsgenQuiet : public ::testing::Test {
 protected:
  void SetUp() override { std::filesystem::create_directories(dir_); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Outcome generate(const std::filesystem::path& idl) const {
    const auto source = wbi::test::source_dir();
    wbi::test::ChildProcess cmake(
        WBI_CMAKE_COMMAND,
        {"-DFASTDDSGEN=" + std::string(WBI_FASTDDSGEN), "-DIDL=" + idl.string(),
         "-DINCLUDE_DIR=" + idl.parent_path().string(), "-DOUT_DIR=" + dir_.string(), "-P",
         (source / "idl" / "run_fastddsgen.cmake").string()});
    const auto code = cmake.wait(120s);
    return {code.value_or(-1), cmake.output()};
  }

  std::filesystem::path dir_ = std::filesystem::temp_directory_path() /
                               ("wbi_fastddsgen_quiet_" + std::to_string(::getpid()));
};

TEST_F(FastddsgenQuiet, PrintsNothingWhenItSucceeds) {
  const auto run = generate(wbi::test::source_dir() / "idl" / "sensors.idl");
  EXPECT_EQ(run.code, 0) << run.output;
  EXPECT_EQ(run.output, "");
  EXPECT_TRUE(std::filesystem::exists(dir_ / "sensorsPubSubTypes.cxx"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "sensorsTypeObject.cxx"));
  // fastddsgen also generates the included common.idl: not into OUT_DIR, where
  // it would overwrite the common.idl rule's files.
  EXPECT_FALSE(std::filesystem::exists(dir_ / "common.h"));
}

TEST_F(FastddsgenQuiet, PrintsOnlyTheErrorAndFailsOnABadFile) {
  const auto bad = dir_ / "bad.idl";
  std::ofstream(bad) << "module m {\nstruct A { longg x; };\n};\n";
  const auto run = generate(bad);
  EXPECT_NE(run.code, 0) << run.output;
  EXPECT_NE(run.output.find("bad.idl:2:11: error: 'longg' was not defined previously"),
            std::string::npos)
      << run.output;
  EXPECT_EQ(run.output.find("Loading templates"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("NullPointerException"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find('\x1b'), std::string::npos) << "colour codes left: " << run.output;
}

// fastddsgen also parses every included file on its own, and exits 0 when that
// fails: here inc.idl uses a macro only main.idl defines; in the build, the
// common.idl emptied by another run when all shared /tmp/common.idl.cc.
TEST_F(FastddsgenQuiet, FailsOnAnErrorLineEvenWhenFastddsgenExitsZero) {
  std::ofstream(dir_ / "main.idl") << "#define T long\n#include \"inc.idl\"\nstruct B { A a; };\n";
  std::ofstream(dir_ / "inc.idl") << "struct A { T x; };\n";
  const auto run = generate(dir_ / "main.idl");
  EXPECT_NE(run.code, 0) << run.output;
  EXPECT_NE(run.output.find("inc.idl:1:11: error: 'T' was not defined previously"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("though it exited 0"), std::string::npos) << run.output;
}

}  // namespace
