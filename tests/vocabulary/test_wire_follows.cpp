// The IDL follows the vocabulary: each wire enum lists the same names, in the
// same order, as the vocabulary's to_string spells them (the values are
// checked at compile time by wire_vocabulary.hpp; the names only here).
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include <wbi/msg/idl_text.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

namespace {

// The enumerators of `enum NAME { ... };` in an IDL text, comments removed.
std::vector<std::string> idl_enumerators(const std::string& idl, const std::string& name) {
  const std::string text = std::regex_replace(idl, std::regex("//[^\n]*"), "");
  std::smatch block;
  if (!std::regex_search(text, block, std::regex("enum\\s+" + name + "\\s*\\{([^}]*)\\}"))) {
    return {};
  }
  std::vector<std::string> names;
  const std::string body = block[1];
  const std::regex identifier("[A-Za-z_][A-Za-z0-9_]*");
  for (auto it = std::sregex_iterator(body.begin(), body.end(), identifier);
       it != std::sregex_iterator(); ++it) {
    names.push_back(it->str());
  }
  return names;
}

template <class Enum>
std::vector<std::string> vocabulary_names() {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < wbi::enum_count<Enum>(); ++i) {
    names.emplace_back(to_string(static_cast<Enum>(i)));
  }
  return names;
}

TEST(WireFollowsVocabulary, ControlMode) {
  EXPECT_EQ(idl_enumerators(wbi::msg::idl_text_for("wbi::msg::ActuatorCommand"), "ControlMode"),
            vocabulary_names<wbi::ControlMode>());
}

TEST(WireFollowsVocabulary, LifecycleState) {
  EXPECT_EQ(idl_enumerators(wbi::msg::idl_text_for("wbi::msg::ComponentStatus"), "LifecycleState"),
            vocabulary_names<wbi::LifecycleState>());
}

TEST(WireFollowsVocabulary, SensorKind) {
  EXPECT_EQ(idl_enumerators(wbi::msg::idl_text_for("wbi::msg::RobotDescription"), "SensorKind"),
            vocabulary_names<wbi::SensorKind>());
}

TEST(WireFollowsVocabulary, ConversionsAreValueForValueAndRangeChecked) {
  EXPECT_EQ(wbi::msg::to_wire(wbi::ControlMode::torque), wbi::msg::TORQUE);
  EXPECT_EQ(wbi::msg::to_wire(wbi::SensorKind::imu), wbi::msg::IMU);
  EXPECT_EQ(wbi::msg::from_wire(wbi::msg::ACTIVE), wbi::LifecycleState::active);
  EXPECT_FALSE(wbi::msg::from_wire(static_cast<wbi::msg::ControlMode>(77)));
}

}  // namespace
