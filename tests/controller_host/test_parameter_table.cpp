// Declared parameters: defaults, checks with one-line refusals, and changes
// that apply whole between two ticks.
#include <gtest/gtest.h>

#include <wbi/controllers/parameter_table.hpp>
#include <wbi/types.hpp>

namespace {

using wbi::controllers::kPerJoint;
using wbi::controllers::ParameterSpec;
using wbi::controllers::ParameterTable;

std::vector<ParameterSpec> specs() {
  return {{.name = "target", .unit = "rad", .size = kPerJoint},
          {.name = "gain_scale", .default_value = {1.0}, .min = 0.0, .max = 10.0},
          {.name = "bandwidth_hz",
           .unit = "Hz",
           .default_value = {5.0},
           .min = 0.001,
           .max = 200.0,
           .live = false},
          {.name = "kp", .size = kPerJoint, .min = 0.0, .optional = true},
          {.name = "offsets", .default_value = {0.5}, .size = kPerJoint}};
}

TEST(ParameterTable, DefaultsFillEveryJoint) {
  ParameterTable table("pd", specs());
  table.size_for(3);
  EXPECT_FALSE(table.is_set(table.index("target")));
  EXPECT_FALSE(table.is_set(table.index("kp")));
  EXPECT_EQ(table.value(table.index("gain_scale")), 1.0);
  const auto offsets = table.values(table.index("offsets"));
  ASSERT_EQ(offsets.size(), 3u);
  EXPECT_EQ(offsets[2], 0.5);
}

TEST(ParameterTable, RefusalsNameParameterValueAndRange) {
  ParameterTable table("pd", specs());
  table.size_for(3);
  const std::vector<double> too_big{20.0};
  EXPECT_EQ(table.check(table.index("gain_scale"), too_big, false),
            "pd: gain_scale = 20 is outside [0, 10]");
  const std::vector<double> two{1.0, 2.0};
  EXPECT_EQ(table.check(table.index("target"), two, false),
            "pd: target takes 3 values (one per controlled joint), got 2");
  const std::vector<double> ten{10.0};
  EXPECT_EQ(table.check(table.index("bandwidth_hz"), ten, true),
            "pd: bandwidth_hz cannot change while the controller is active (deactivate it first)");
  EXPECT_EQ(table.check(table.index("bandwidth_hz"), ten, false), "");
  const std::vector<double> nan{std::nan("")};
  EXPECT_NE(table.check(table.index("gain_scale"), nan, false), "");
  EXPECT_THROW(table.stage(table.index("gain_scale"), too_big, true), wbi::Error);
  try {
    (void)table.index("gian_scale");
    FAIL() << "an unknown name is refused";
  } catch (const wbi::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no parameter 'gian_scale'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("gain_scale"), std::string::npos) << "lists the known";
  }
}

TEST(ParameterTable, StagedValuesApplyOnlyBetweenTicks) {
  ParameterTable table("pd", specs());
  table.size_for(2);
  const std::size_t target = table.index("target");
  table.set(target, std::vector<double>{0.1, 0.2});
  const auto generation = table.generation();
  table.stage(target, std::vector<double>{1.0, 2.0}, true);
  EXPECT_EQ(table.values(target)[1], 0.2) << "not before apply_staged";
  EXPECT_TRUE(table.apply_staged());
  EXPECT_EQ(table.values(target)[0], 1.0);
  EXPECT_EQ(table.values(target)[1], 2.0);
  EXPECT_GT(table.generation(), generation);
  EXPECT_FALSE(table.apply_staged()) << "nothing staged";
}

TEST(ParameterTable, ADefaultThatDoesNotFitIsAnError) {
  ParameterTable table("pd", {{.name = "pair", .default_value = {1.0, 2.0, 3.0}, .size = 2}});
  EXPECT_THROW(table.size_for(4), wbi::Error);
}

}  // namespace
