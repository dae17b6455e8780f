// The state estimates a controller answers, one cycle each: a state answered
// already is skipped (update() returns false), and the controller's time is
// the state's source time since the first state it answered, so that a
// lockstep run's figures do not depend on the host's clock.
#pragma once

#include <cstdint>

#include "wbi/whole_body_interface.hpp"

namespace wbi::controllers {

class AnsweredStates {
 public:
  // A new activation: the next state answered is the first.
  void reset() { answered_ = 0; }
  // False when `stamp`'s estimate was answered already; else it becomes the
  // one being answered.
  bool take(const Stamp& stamp) {
    if (answered_ > 0 && stamp.seq == last_seq_) {
      return false;
    }
    if (answered_++ == 0) {
      start_ns_ = stamp.source_ns;
    }
    last_seq_ = stamp.seq;
    stamp_ns_ = stamp.source_ns;
    return true;
  }
  bool first() const { return answered_ == 1; }  // the one being answered is the first
  std::int64_t stamp_ns() const { return stamp_ns_; }
  double time_s() const { return 1e-9 * static_cast<double>(stamp_ns_ - start_ns_); }

 private:
  std::uint64_t answered_ = 0, last_seq_ = 0;
  std::int64_t start_ns_ = 0, stamp_ns_ = 0;
};

}  // namespace wbi::controllers
