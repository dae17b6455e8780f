// reset(), wrong sizes and bad parameters: clear errors, no hidden state.
#include <gtest/gtest.h>

#include <string>

#include "estimation_helpers.hpp"
#include "wbi/estimation/low_pass_filter.hpp"

namespace wbi::estimation::test {
namespace {

double wave(double t) { return 0.3 * std::sin(7.0 * t) + 0.1 * t; }

// Expects `call` to throw std::invalid_argument whose message contains `text`.
template <typename Call>
void expect_error(Call call, const std::string& text) {
  try {
    call();
    ADD_FAILURE() << "no error; expected one containing '" << text << "'";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
  }
}

TEST(Reset, RestartsLikeANewEstimator) {
  for (const auto& method : all_methods()) {
    const auto used = make_estimator(method, 3);
    feed(*used, regular_stamps(500), wave);
    used->reset();
    Eigen::VectorXd q = Eigen::VectorXd::Constant(3, 0.2);
    EXPECT_EQ(used->update(stamp_at(0), q), SampleStatus::first) << method;  // older stamp accepted
    EXPECT_EQ(used->velocity(), Eigen::VectorXd::Zero(3)) << method;
    used->reset();
    const auto fresh = make_estimator(method, 3);
    const auto later = regular_stamps(300);
    feed(*used, later, wave);
    feed(*fresh, later, wave);
    EXPECT_EQ(used->velocity(), fresh->velocity()) << method;
    EXPECT_EQ(used->acceleration(), fresh->acceleration()) << method;
    // Counters survive reset() and clear with reset_counters().
    EXPECT_GT(used->stamp_counters().accepted, fresh->stamp_counters().accepted) << method;
    used->reset_counters();
    EXPECT_EQ(used->stamp_counters().accepted, 0u) << method;
  }
}

TEST(Sizes, WrongSizeIsAClearError) {
  for (const auto& method : all_methods()) {
    const auto estimator = make_estimator(method, 4);
    EXPECT_EQ(estimator->joints(), 4);
    EXPECT_EQ(estimator->velocity().size(), 4);
    EXPECT_EQ(estimator->acceleration().size(), 4);
    expect_error([&] { estimator->update(0, Eigen::VectorXd::Zero(3)); },
                 "q has 3 values, expected 4");
    expect_error([&] { make_estimator(method, 0); }, "at least one joint");
  }
  LowPassFilter filter(6, 10.0);
  expect_error([&] { filter.update(0, Eigen::VectorXd::Zero(5)); }, "x has 5 values, expected 6");
}

TEST(Factory, ListsTheMethods) {
  const auto names = method_names();
  ASSERT_GE(names.size(), 3u);
  EXPECT_EQ(names[0], "split-kalman");  // the recommended one first
  for (const auto& name : names) {
    EXPECT_EQ(make_estimator(name, 1)->method(), name);
  }
}

TEST(Factory, BadMethodsAndParametersAreNamed) {
  expect_error([] { make_estimator("savgol", 2); }, "unknown estimation method 'savgol'");
  expect_error(
      [] {
        make_estimator("kalman", 2, {{"threshold", 1.0}});
      },
      "method 'kalman' has no parameter 'threshold'");
  expect_error(
      [] {
        make_estimator("adaptive-window", 2, {{"velocity-window", 1.0}});
      },
      "'velocity-window' must be an integer in [2, 1000], got 1");
  expect_error(
      [] {
        make_estimator("adaptive-window", 2, {{"acceleration-window", 4.5}});
      },
      "'acceleration-window' must be an integer");
  expect_error(
      [] {
        make_estimator("adaptive-window", 2, {{"threshold", -1.0}});
      },
      "'threshold' must be a number");
  expect_error([] { make_estimator("backward-difference", 2, {{"cutoff", -3.0}}); }, "'cutoff'");
  expect_error([] { make_estimator("kalman", 2, {{"model-order", 5.0}}); }, "'model-order'");
  expect_error(
      [] {
        make_estimator("kalman", 2, {{"sample-rate", 1000.0}, {"max-gap", 0.001}});
      },
      "max-gap must exceed 1.5 sample periods");
  EXPECT_NO_THROW(make_estimator("adaptive-window", 2,
                                 {{"velocity-window", 8},
                                  {"acceleration-window", 12},
                                  {"threshold", 0.01},
                                  {"sample-rate", 500}}));
  expect_error([] { LowPassFilter(0, 1.0); }, "size must be > 0");
  expect_error([] { LowPassFilter(1, -1.0); }, "cutoff must be >= 0 Hz");
}

}  // namespace
}  // namespace wbi::estimation::test
