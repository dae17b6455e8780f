// A controller's reference output: what a planner hosted with the controller
// it feeds writes into that controller's reference input, in the same tick
// (chaining, controller.hpp). The host connects an output to an input of the
// same size when the deploy file says so (`inputs: {com: planner}` on the
// controller that reads it), and runs the planner's update() first: the
// point arrives without DDS and without a tick of delay. Unconnected, a
// write goes nowhere (counted).
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "wbi/controllers/reference_input.hpp"

namespace wbi::controllers {

class ReferenceOutput {
 public:
  // owner: "<controller>/<output>" for error texts.
  ReferenceOutput(std::string owner, ReferenceSpec spec);
  ReferenceOutput(const ReferenceOutput&) = delete;
  ReferenceOutput& operator=(const ReferenceOutput&) = delete;

  const ReferenceSpec& spec() const { return spec_; }
  const std::string& owner() const { return owner_; }

  // Setup: where written points go. Throws wbi::Error naming both when the
  // sizes differ or it is connected already.
  void connect(ReferenceInput& input);
  bool connected() const { return input_ != nullptr; }

  // Loop thread, in update(): the point for robot time stamp_ns (the state's
  // source stamp). velocity and acceleration: spec().size values, or empty
  // (zero). Throws wbi::Error naming the output on another size. No allocation.
  void write(std::int64_t stamp_ns, std::span<const double> position,
             std::span<const double> velocity = {}, std::span<const double> acceleration = {});

  std::uint64_t written() const { return written_; }
  std::uint64_t unconnected() const { return unconnected_; }  // writes that went nowhere

 private:
  const std::string owner_;
  const ReferenceSpec spec_;
  ReferenceInput* input_ = nullptr;
  TrajectoryPoint point_;
  std::uint64_t written_ = 0, unconnected_ = 0;
};

}  // namespace wbi::controllers
