#include "wbi/controllers/parameter_table.hpp"

#include <cmath>
#include <cstdio>

#include <wbi/types.hpp>

namespace wbi::controllers {

namespace {
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

std::string range_text(const ParameterSpec& spec) {
  std::string text = "[";
  text += number(spec.min);
  text += ", ";
  text += number(spec.max);
  text += "]";
  if (!spec.unit.empty()) {
    text += " ";
    text += spec.unit;
  }
  return text;
}
}  // namespace

std::string format_values(std::span<const double> values) {
  if (values.size() == 1) {
    return number(values[0]);
  }
  std::string text = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) {
      text += ", ";
    }
    text += number(values[i]);
  }
  return text + "]";
}

ParameterTable::ParameterTable(std::string owner, std::vector<ParameterSpec> specs)
    : owner_(std::move(owner)) {
  for (auto& spec : specs) {
    if (find(spec.name)) {
      throw Error(owner_ + ": parameter '" + spec.name + "' is declared twice");
    }
    Entry entry;
    entry.spec = std::move(spec);
    entries_.push_back(std::move(entry));
  }
}

int ParameterTable::expected_count(const ParameterSpec& spec) const {
  return spec.size == kPerJoint ? joints_ : spec.size;
}

void ParameterTable::size_for(int joints) {
  joints_ = joints;
  for (auto& entry : entries_) {
    entry.count = expected_count(entry.spec);
    entry.values.reserve(static_cast<std::size_t>(entry.count));
    entry.staged.reserve(static_cast<std::size_t>(entry.count));
    const auto& fallback = entry.spec.default_value;
    entry.values.clear();
    if (entry.spec.text) {
      entry.count = 0;
      entry.text = entry.spec.text_default;
      continue;
    }
    if (fallback.size() == 1 && entry.count > 1) {
      entry.values.assign(static_cast<std::size_t>(entry.count), fallback[0]);
    } else if (!fallback.empty()) {
      if (const std::string problem =
              check(static_cast<std::size_t>(&entry - entries_.data()), fallback, false);
          !problem.empty()) {
        throw Error(problem + " (its default)");
      }
      entry.values = fallback;
    }
  }
  generation_.fetch_add(1, std::memory_order_acq_rel);
}

std::optional<std::size_t> ParameterTable::find(std::string_view name) const {
  for (std::size_t i = 0; i < entries_.size(); ++i) {
    if (entries_[i].spec.name == name) {
      return i;
    }
  }
  return std::nullopt;
}

std::size_t ParameterTable::index(std::string_view name) const {
  if (const auto found = find(name)) {
    return *found;
  }
  std::string known;
  for (const auto& entry : entries_) {
    known += (known.empty() ? "" : ", ") + entry.spec.name;
  }
  throw Error(owner_ + ": no parameter '" + std::string(name) +
              "' (declared: " + (known.empty() ? "none" : known) + ")");
}

std::vector<double> ParameterTable::snapshot(std::size_t index) const {
  std::lock_guard lock(mutex_);
  return entries_.at(index).values;
}

std::string ParameterTable::text(std::size_t index) const {
  std::lock_guard lock(mutex_);
  return entries_.at(index).text;
}

void ParameterTable::set_text(std::size_t index, const std::string& value) {
  Entry& entry = entries_.at(index);
  if (!entry.spec.text) {
    throw Error(owner_ + ": " + entry.spec.name + " takes numbers, not text ('" + value + "')");
  }
  std::lock_guard lock(mutex_);
  entry.text = value;
  generation_.fetch_add(1, std::memory_order_acq_rel);
}

std::string ParameterTable::check(std::size_t index, std::span<const double> values,
                                  bool active) const {
  const Entry& entry = entries_.at(index);
  const ParameterSpec& spec = entry.spec;
  if (spec.text) {
    return owner_ + ": " + spec.name + " takes a text, not numbers";
  }
  const std::string named = owner_ + ": " + spec.name + " = " + format_values(values);
  if (active && !spec.live) {
    return owner_ + ": " + spec.name +
           " cannot change while the controller is active (deactivate it first)";
  }
  if (values.empty() && spec.optional) {
    return "";
  }
  if (static_cast<int>(values.size()) != entry.count) {
    return owner_ + ": " + spec.name + " takes " + std::to_string(entry.count) +
           (entry.count == 1 ? " value" : " values") +
           (spec.size == kPerJoint ? " (one per controlled joint)" : "") + ", got " +
           std::to_string(values.size());
  }
  for (const double value : values) {
    if (!std::isfinite(value) || value < spec.min || value > spec.max) {
      return named + " is outside " + range_text(spec);
    }
  }
  return "";
}

void ParameterTable::set(std::size_t index, std::span<const double> values) {
  if (const std::string problem = check(index, values, false); !problem.empty()) {
    throw Error(problem);
  }
  std::lock_guard lock(mutex_);
  entries_[index].values.assign(values.begin(), values.end());
  generation_.fetch_add(1, std::memory_order_acq_rel);
}

void ParameterTable::stage(std::size_t index, std::span<const double> values, bool active) {
  if (const std::string problem = check(index, values, active); !problem.empty()) {
    throw Error(problem);
  }
  std::lock_guard lock(mutex_);
  Entry& entry = entries_[index];
  entry.staged.assign(values.begin(), values.end());
  entry.has_staged = true;
  any_staged_.store(true, std::memory_order_release);
}

bool ParameterTable::apply_staged() {
  if (!any_staged_.load(std::memory_order_acquire)) {
    return false;
  }
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) {
    return false;  // being staged right now: applied at the next tick
  }
  for (auto& entry : entries_) {
    if (entry.has_staged) {
      // Within the capacity reserved by size_for(): no allocation.
      entry.values.assign(entry.staged.begin(), entry.staged.end());
      entry.has_staged = false;
    }
  }
  any_staged_.store(false, std::memory_order_release);
  generation_.fetch_add(1, std::memory_order_acq_rel);
  return true;
}

}  // namespace wbi::controllers
