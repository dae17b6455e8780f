// The IDL follows the vocabulary: each wire enum lists the same names, in the
// same order, as the vocabulary's to_string spells them (the values are
// checked at compile time by wire_vocabulary.hpp; the names only here).
#include <gtest/gtest.h>

#include <cctype>
#include <string>
#include <vector>

#include <wbi/msg/idl_text.hpp>
#include <wbi/msg/wire_vocabulary.hpp>

namespace {

// The enumerators of `enum NAME { ... };` in an IDL text, comments removed.
// Plain scanning, not std::regex (whose code g++ 12 flags with
// -Wmaybe-uninitialized at -O1, the sanitizer build's level).
std::vector<std::string> idl_enumerators(const std::string& idl, const std::string& name) {
  std::string text;
  for (std::size_t i = 0; i < idl.size(); ++i) {
    if (idl.compare(i, 2, "//") == 0) {
      i = idl.find('\n', i);
      if (i == std::string::npos) {
        break;
      }
    }
    text += idl[i];
  }
  const std::size_t start = text.find("enum " + name + " {");
  if (start == std::string::npos) {
    return {};
  }
  const std::size_t open = text.find('{', start);
  const std::size_t close = text.find('}', open);
  std::vector<std::string> names;
  std::string word;
  for (std::size_t i = open + 1; i <= close; ++i) {
    const char c = text[i];
    if (std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_') {
      word += c;
    } else if (!word.empty()) {
      names.push_back(word);
      word.clear();
    }
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

TEST(WireFollowsVocabulary, EventSeverityAndKind) {
  const std::string text = wbi::msg::idl_text_for("wbi::msg::Event");
  EXPECT_EQ(idl_enumerators(text, "EventSeverity"), vocabulary_names<wbi::EventSeverity>());
  EXPECT_EQ(idl_enumerators(text, "EventKind"), vocabulary_names<wbi::EventKind>());
}

TEST(WireFollowsVocabulary, ConversionsAreValueForValueAndRangeChecked) {
  EXPECT_EQ(wbi::msg::to_wire(wbi::ControlMode::torque), wbi::msg::TORQUE);
  EXPECT_EQ(wbi::msg::to_wire(wbi::SensorKind::imu), wbi::msg::IMU);
  EXPECT_EQ(wbi::msg::from_wire(wbi::msg::ACTIVE), wbi::LifecycleState::active);
  EXPECT_FALSE(wbi::msg::from_wire(static_cast<wbi::msg::ControlMode>(77)));
}

}  // namespace
