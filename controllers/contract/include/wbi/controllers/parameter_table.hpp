// A controller's declared parameters and their current values.
//
// A controller declares each parameter once (ParameterSpec: name, unit, range,
// default, size, whether it may change while the controller is active). The
// controller host fills the values from the deploy file at configure and checks
// every later change against the declaration. A change is staged on any thread
// and applied by the loop between two ticks (apply_staged), all of it at once:
// a tick never sees half of a change.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace wbi::controllers {

// ParameterSpec::size for a parameter with one value per controlled joint.
inline constexpr int kPerJoint = -1;

struct ParameterSpec {
  // Every member has a default ({}): designated initializers name only what differs.
  std::string name{};
  std::string unit{};                   // SI, e.g. "rad", "Hz", "1/s^2"; "" for a pure number
  std::string help{};                   // one line
  std::vector<double> default_value{};  // empty: none (the parameter is then required or optional)
  int size = 1;                         // number of values, or kPerJoint
  double min = -std::numeric_limits<double>::infinity();  // of each value
  double max = std::numeric_limits<double>::infinity();
  bool live = true;       // may change while the controller is active
  bool optional = false;  // may stay unset (no values): the controller derives it
  // A text parameter (a frame name, say): one string, text_default, no
  // numbers; read at configure only.
  bool text = false;
  std::string text_default{};
};

// A number with its default and range, the common case of a spec.
inline ParameterSpec number_parameter(const char* name, const char* unit, double value, double min,
                                      double max, bool live, const char* help) {
  return {.name = name,
          .unit = unit,
          .help = help,
          .default_value = {value},
          .min = min,
          .max = max,
          .live = live};
}

class ParameterTable {
 public:
  // owner: the controller's name, in error texts ("pd: kp_scale = 7 is outside [0, 4]").
  ParameterTable(std::string owner, std::vector<ParameterSpec> specs);
  ParameterTable(const ParameterTable&) = delete;
  ParameterTable& operator=(const ParameterTable&) = delete;

  // Sizes the per-joint parameters and sets the defaults (a per-joint default
  // of one value is repeated for every joint). Throws wbi::Error naming a
  // default that does not fit its declaration.
  void size_for(int joints);

  const std::string& owner() const { return owner_; }
  std::size_t size() const { return entries_.size(); }
  const ParameterSpec& spec(std::size_t index) const { return entries_.at(index).spec; }
  std::optional<std::size_t> find(std::string_view name) const;
  // Throws wbi::Error naming the parameter and the declared ones.
  std::size_t index(std::string_view name) const;

  // Loop thread (or before the controller runs): the current values. Empty
  // for an optional parameter left unset.
  std::span<const double> values(std::size_t index) const { return entries_[index].values; }
  double value(std::size_t index) const { return entries_[index].values.at(0); }
  bool is_set(std::size_t index) const { return !entries_[index].values.empty(); }
  // A copy of the current values, from any thread.
  std::vector<double> snapshot(std::size_t index) const;
  // A text parameter's value.
  std::string text(std::size_t index) const;
  // Sets a text parameter, before the controller is configured. Throws
  // wbi::Error naming a parameter that is not a text one.
  void set_text(std::size_t index, const std::string& value);

  // "" when `values` may become the parameter's values now, else one line
  // naming the parameter, the value and what was expected.
  std::string check(std::size_t index, std::span<const double> values, bool active) const;
  // Sets at once, before the controller runs (configure). Throws wbi::Error (check's text).
  void set(std::size_t index, std::span<const double> values);
  // Any thread, while the loop runs: checks (throws wbi::Error with check's
  // text) and stages the values for the next apply_staged().
  void stage(std::size_t index, std::span<const double> values, bool active);
  // Loop thread, between ticks: applies every staged change. Never blocks
  // (a change being staged right now waits for the next tick) and allocates
  // nothing. True when something changed.
  bool apply_staged();
  // +1 at every set() or applied change.
  std::uint64_t generation() const { return generation_.load(std::memory_order_acquire); }

 private:
  struct Entry {
    ParameterSpec spec;
    int count = 1;               // values after size_for()
    std::vector<double> values;  // current; capacity `count`
    std::vector<double> staged;  // capacity `count`
    bool has_staged = false;
    std::string text;  // a text parameter's value
  };
  int expected_count(const ParameterSpec& spec) const;

  std::string owner_;
  int joints_ = 0;
  std::vector<Entry> entries_;
  mutable std::mutex mutex_;  // stage() and readers on other threads against apply_staged()
  std::atomic<bool> any_staged_{false};
  std::atomic<std::uint64_t> generation_{0};
};

// "1.5" or "[1, 2, 3]", as the refusals and `wbi param get` print values.
std::string format_values(std::span<const double> values);

}  // namespace wbi::controllers
