#include "wbi/controllers/reference_input.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>

#include <wbi/types.hpp>

namespace wbi::controllers {

const char* to_string(StaleRule rule) {
  switch (rule) {
    case StaleRule::hold_last:
      return "hold_last";
    case StaleRule::decay_to_state:
      return "decay_to_state";
    case StaleRule::fall_back:
      return "fall_back";
  }
  return "?";
}

ReferenceInput::ReferenceInput(std::string owner, ReferenceSpec spec)
    : owner_(std::move(owner)), spec_(std::move(spec)) {
  if (spec_.size < 1 || spec_.size > kMaxReferenceValues) {
    throw Error(owner_ + ": a reference input takes 1 to " + std::to_string(kMaxReferenceValues) +
                " values, not " + std::to_string(spec_.size));
  }
  if (!(spec_.max_age_s > 0.0) || !(spec_.decay_s > 0.0)) {
    throw Error(owner_ + ": max_age_s and decay_s must be > 0");
  }
  position_.setZero(spec_.size);
  velocity_.setZero(spec_.size);
  acceleration_.setZero(spec_.size);
}

bool ReferenceInput::push(const TrajectoryPoint& point) {
  {
    std::lock_guard lock(mutex_);
    if (point.size != spec_.size) {
      ++malformed_;
      return false;
    }
    if (received_ > 0 && point.stamp_ns < newest_stamp_ns_) {
      // Time went back: a new robot (a restarted simulation starts at 0) or a
      // restarted generator. What was queued is another run's.
      count_ = 0;
      newest_stamp_ns_ = point.stamp_ns;
      restarted_ = true;
      ++restarts_;
    }
    if (count_ == kCapacity) {
      // Nobody takes them (an inactive controller), or a generator far ahead:
      // the oldest point is the least useful.
      head_ = (head_ + 1) % kCapacity;
      --count_;
      ++overwritten_;
    }
    queue_[(head_ + count_) % kCapacity] = point;
    ++count_;
    ++received_;
    wait_timed_out_ = false;  // it is fed again: the ticks wait for it
    newest_stamp_ns_ = std::max(newest_stamp_ns_, point.stamp_ns);
  }
  arrived_.notify_all();
  return true;
}

bool ReferenceInput::wait_for(std::int64_t time_ns, std::int64_t timeout_ns) {
  std::unique_lock lock(mutex_);
  if (arrived_.wait_for(lock, std::chrono::nanoseconds(timeout_ns),
                        [&] { return received_ > 0 && newest_stamp_ns_ >= time_ns; })) {
    return true;
  }
  ++late_;
  return false;
}

bool ReferenceInput::ready_for(std::int64_t time_ns, bool first) const {
  std::lock_guard lock(mutex_);
  const bool point_in = received_ > 0 && newest_stamp_ns_ >= time_ns;
  if (first) {
    return point_in;
  }
  return wait_ns_ <= 0 || received_ == 0 || wait_timed_out_ || point_in;
}

void ReferenceInput::wait_if_fed(std::int64_t time_ns) {
  std::unique_lock lock(mutex_);
  if (received_ == 0 || wait_timed_out_) {
    return;  // nobody feeds it (yet), or no more since a wait timed out
  }
  if (!arrived_.wait_for(lock, std::chrono::nanoseconds(wait_ns_),
                         [&] { return newest_stamp_ns_ >= time_ns; })) {
    // Its generator is late, or dead: then waiting every tick would slow the
    // run to one tick per wait_ns. The next point ends this.
    ++late_;
    wait_timed_out_ = true;
  }
}

std::uint64_t ReferenceInput::received() const {
  std::lock_guard lock(mutex_);
  return received_;
}

std::uint64_t ReferenceInput::restarts() const {
  std::lock_guard lock(mutex_);
  return restarts_;
}

std::uint64_t ReferenceInput::late() const {
  std::lock_guard lock(mutex_);
  return late_;
}

std::uint64_t ReferenceInput::malformed() const {
  std::lock_guard lock(mutex_);
  return malformed_;
}

std::uint64_t ReferenceInput::overwritten() const {
  std::lock_guard lock(mutex_);
  return overwritten_;
}

std::string ReferenceInput::summary() const {
  char text[320];
  std::lock_guard lock(mutex_);
  std::snprintf(
      text, sizeof text,
      "reference %s: %llu points (%llu malformed, %llu overwritten unused, %llu "
      "restarts); ticks: %llu carried from an earlier point, %llu stale in %llu "
      "episodes (rule %s), %llu before the first point; %llu points late",
      owner_.c_str(), static_cast<unsigned long long>(received_),
      static_cast<unsigned long long>(malformed_), static_cast<unsigned long long>(overwritten_),
      static_cast<unsigned long long>(restarts_), static_cast<unsigned long long>(carried_ticks_),
      static_cast<unsigned long long>(stale_ticks_),
      static_cast<unsigned long long>(stale_episodes_), to_string(spec_.rule),
      static_cast<unsigned long long>(missing_ticks_), static_cast<unsigned long long>(late_));
  return text;
}

void ReferenceInput::take_due(std::int64_t time_ns) {
  // Held by push() for one point's copy at most: a point pushed right now
  // may be this tick's (a lockstep generator's), so it is waited for.
  std::lock_guard lock(mutex_);
  if (restarted_ || (has_current_ && current_.stamp_ns > time_ns)) {
    has_current_ = false;  // the held point is another run's (time went back)
    restarted_ = false;
  }
  while (count_ > 0 && queue_[head_].stamp_ns <= time_ns) {
    current_ = queue_[head_];
    has_current_ = true;
    head_ = (head_ + 1) % kCapacity;
    --count_;
  }
}

bool ReferenceInput::follow(std::int64_t time_ns) {
  if (wait_ns_ > 0) {
    wait_if_fed(time_ns);
  }
  take_due(time_ns);
  const double age_s = has_current_ ? 1e-9 * static_cast<double>(time_ns - current_.stamp_ns) : 0.0;
  if (has_current_ && age_s <= spec_.max_age_s) {
    const int n = spec_.size;
    const Eigen::Map<const Eigen::VectorXd> x(current_.position.data(), n);
    const Eigen::Map<const Eigen::VectorXd> v(current_.velocity.data(), n);
    const Eigen::Map<const Eigen::VectorXd> a(current_.acceleration.data(), n);
    if (age_s == 0.0) {
      position_ = x;  // bit for bit what was sent: a lockstep run is reproducible
      velocity_ = v;
    } else {
      ++carried_ticks_;
      position_ = x + age_s * v + (0.5 * age_s * age_s) * a;
      velocity_ = v + age_s * a;
    }
    acceleration_ = a;
    stale_since_ns_ = -1;
    return true;
  }
  return false;
}

void ReferenceInput::apply_rule(std::int64_t time_ns,
                                const Eigen::Ref<const Eigen::VectorXd>& measured) {
  ++(has_current_ ? stale_ticks_ : missing_ticks_);
  if (stale_since_ns_ < 0) {
    stale_since_ns_ = time_ns;
    if (has_current_) {
      ++stale_episodes_;
    }
  }
  velocity_.setZero();
  acceleration_.setZero();
  if (!has_current_) {
    position_ = measured;  // nothing to hold yet: stay where the robot is
    return;
  }
  const Eigen::Map<const Eigen::VectorXd> last(current_.position.data(), spec_.size);
  switch (spec_.rule) {
    case StaleRule::hold_last:
      position_ = last;
      return;
    case StaleRule::decay_to_state: {
      const double since_s = 1e-9 * static_cast<double>(time_ns - stale_since_ns_);
      const double kept = std::exp(-since_s / spec_.decay_s);
      position_ = measured + kept * (last - measured);
      return;
    }
    case StaleRule::fall_back: {
      char text[160];
      std::snprintf(text, sizeof text, "reference %s is %.3f s old (bound %.3f s)", owner_.c_str(),
                    1e-9 * static_cast<double>(time_ns - current_.stamp_ns), spec_.max_age_s);
      throw Error(text);
    }
  }
}

}  // namespace wbi::controllers
