#include "wbi/controllers/reference_output.hpp"

#include <algorithm>

#include <wbi/types.hpp>

namespace wbi::controllers {

ReferenceOutput::ReferenceOutput(std::string owner, ReferenceSpec spec)
    : owner_(std::move(owner)), spec_(std::move(spec)) {
  if (spec_.size < 1 || spec_.size > kMaxReferenceValues) {
    throw Error("reference output " + owner_ + ": size " + std::to_string(spec_.size) +
                " is outside [1, " + std::to_string(kMaxReferenceValues) + "]");
  }
  point_.size = spec_.size;
}

void ReferenceOutput::connect(ReferenceInput& input) {
  if (input_) {
    throw Error("reference output " + owner_ + " is chained to " + input_->owner() +
                " already, not also to " + input.owner());
  }
  if (input.spec().size != spec_.size) {
    throw Error("reference output " + owner_ + " has " + std::to_string(spec_.size) +
                " values, the input " + input.owner() + " takes " +
                std::to_string(input.spec().size));
  }
  input_ = &input;
}

void ReferenceOutput::write(std::int64_t stamp_ns, std::span<const double> position,
                            std::span<const double> velocity,
                            std::span<const double> acceleration) {
  const auto size = static_cast<std::size_t>(spec_.size);
  const auto fits = [size](std::span<const double> values, bool optional) {
    return values.size() == size || (optional && values.empty());
  };
  if (!fits(position, false) || !fits(velocity, true) || !fits(acceleration, true)) {
    throw Error("reference output " + owner_ + ": a point has " + std::to_string(size) +
                " values of position and the same or none of velocity and acceleration");
  }
  if (!input_) {
    ++unconnected_;
    return;
  }
  point_.stamp_ns = stamp_ns;
  point_.seq = written_++;
  const auto copy = [size](std::span<const double> from, auto& to) {
    if (from.empty()) {
      std::fill_n(to.begin(), size, 0.0);
    } else {
      std::copy(from.begin(), from.end(), to.begin());
    }
  };
  copy(position, point_.position);
  copy(velocity, point_.velocity);
  copy(acceleration, point_.acceleration);
  input_->push(point_);
}

}  // namespace wbi::controllers
