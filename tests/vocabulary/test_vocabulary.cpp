// The vocabulary's names: one spelling per enumerator, parsed back to itself;
// raw values outside an enum are refused, not cast.
#include <gtest/gtest.h>

#include <string>
#include <wbi/vocabulary.hpp>

namespace {

// Every enumerator's name parses back to it, and no two share a name.
template <class Enum>
void expect_names_round_trip() {
  for (std::size_t i = 0; i < wbi::enum_count<Enum>(); ++i) {
    const auto value = static_cast<Enum>(i);
    const std::string name = to_string(value);
    const auto parsed = wbi::enum_from_name<Enum>(name);
    ASSERT_TRUE(parsed.has_value()) << name;
    EXPECT_EQ(*parsed, value) << name;
  }
}

TEST(Vocabulary, EveryNameParsesBackToItsEnumerator) {
  expect_names_round_trip<wbi::ControlMode>();
  expect_names_round_trip<wbi::LifecycleState>();
  expect_names_round_trip<wbi::SensorKind>();
  expect_names_round_trip<wbi::Integrator>();
  expect_names_round_trip<wbi::ContactShape>();
  expect_names_round_trip<wbi::EventSeverity>();
  expect_names_round_trip<wbi::EventKind>();
}

TEST(Vocabulary, NamesAreTheWiresAndTheConfigFiles) {
  EXPECT_STREQ(to_string(wbi::ControlMode::position_direct), "POSITION_DIRECT");
  EXPECT_STREQ(to_string(wbi::LifecycleState::inactive), "INACTIVE");
  EXPECT_STREQ(to_string(wbi::SensorKind::force_torque), "FORCE_TORQUE");
  EXPECT_STREQ(to_string(wbi::Integrator::rk4), "RK4");  // MuJoCo's XML spelling
  EXPECT_STREQ(to_string(wbi::ContactShape::capsule), "capsule");
}

TEST(Vocabulary, UnknownNamesAndValuesAreRefused) {
  EXPECT_FALSE(wbi::enum_from_name<wbi::ControlMode>("position"));  // exact spelling only
  EXPECT_FALSE(wbi::enum_from_name<wbi::ControlMode>(""));
  EXPECT_EQ(wbi::enum_from_name_any_case<wbi::Integrator>("rk4"), wbi::Integrator::rk4);
  EXPECT_FALSE(wbi::enum_from_name_any_case<wbi::Integrator>("rk"));
  EXPECT_EQ(wbi::enum_from_value<wbi::ControlMode>(5), wbi::ControlMode::pwm);
  EXPECT_FALSE(wbi::enum_from_value<wbi::ControlMode>(6));
  EXPECT_FALSE(wbi::enum_from_value<wbi::ControlMode>(-1));
  EXPECT_FALSE(wbi::enum_from_value<wbi::SensorKind>(0xFFFFFFFFLL));
  EXPECT_STREQ(to_string(static_cast<wbi::LifecycleState>(9)), "?");
}

TEST(Vocabulary, ValuesTextListsEveryValue) {
  EXPECT_EQ(wbi::enum_values_text<wbi::ControlMode>(),
            "0 IDLE, 1 POSITION, 2 POSITION_DIRECT, 3 VELOCITY, 4 TORQUE, 5 PWM");
}

TEST(Vocabulary, StreamingModesAreTheFourWithoutAPlannedTrajectory) {
  EXPECT_FALSE(is_streaming(wbi::ControlMode::idle));
  EXPECT_FALSE(is_streaming(wbi::ControlMode::position));
  EXPECT_TRUE(is_streaming(wbi::ControlMode::position_direct));
  EXPECT_TRUE(is_streaming(wbi::ControlMode::velocity));
  EXPECT_TRUE(is_streaming(wbi::ControlMode::torque));
  EXPECT_TRUE(is_streaming(wbi::ControlMode::pwm));
}

}  // namespace
