// The IDL text compiled into wbi::idl describes each type on its own: it
// names the type and its dependencies, has no preprocessor lines, and
// fastddsgen accepts it as a stand-alone file.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <unistd.h>

#include <wbi/msg/idl_text.hpp>

namespace {

TEST(IdlText, SelfContainedForEveryTopLevelType) {
  for (const char* type :
       {"RobotDescription", "SensorSample", "GroundTruth", "ActuatorCommand", "ControlParameters",
        "StateEstimate", "ModelRequest", "ModelReply", "ComponentStatus", "SimulationClock",
        "PlaybackCommand", "Signals", "JointOwners"}) {
    const std::string text = wbi::msg::idl_text_for(std::string("wbi::msg::") + type);
    EXPECT_NE(text.find(std::string("struct ") + type), std::string::npos) << type;
    EXPECT_NE(text.find("struct Header"), std::string::npos) << type;
    EXPECT_EQ(text.find("#include"), std::string::npos) << type;
    EXPECT_EQ(text.find("#ifndef"), std::string::npos) << type;
  }
}

TEST(IdlText, UnknownTypeIsNamed) {
  try {
    wbi::msg::idl_text_for("wbi::msg::NoSuchType");
    FAIL() << "expected an error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("wbi::msg::NoSuchType"), std::string::npos);
  }
  EXPECT_THROW(wbi::msg::idl_text_for("SensorSample"), std::invalid_argument);
}

TEST(IdlText, FastddsgenAcceptsTheTextAlone) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("wbi_idl_text_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "out");
  {
    std::ofstream out(dir / "sample.idl");
    out << wbi::msg::idl_text_for("wbi::msg::SensorSample");
  }
  // -t: fastddsgen's default temporary folder is /tmp/, shared by every run on
  // the machine (idl/run_fastddsgen.cmake).
  const std::string command = std::string(WBI_FASTDDSGEN) + " -cs -replace -d " +
                              (dir / "out").string() + " -t " + dir.string() + " " +
                              (dir / "sample.idl").string() + " > " + (dir / "log.txt").string() +
                              " 2>&1";
  const int code = std::system(command.c_str());
  std::ifstream log(dir / "log.txt");
  const std::string output((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_EQ(code, 0) << output;
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "sample.h")) << output;
  std::filesystem::remove_all(dir);
}

}  // namespace
