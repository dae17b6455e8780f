// A controller's reference input: trajectory points (position, velocity,
// acceleration for one robot time) from another process, and what the
// controller does when they stop coming.
//
// A controller declares its inputs (ReferenceSpec); the controller host makes
// one ReferenceInput per input, feeds it the points of
// wbi/<robot>/references/<controller>/<input> as they arrive (any thread) and
// hands it to the controller (Controller::bind_references). The controller
// asks it, once per tick, for the reference at its state's stamp (at()):
//   fresh    the newest point stamped at or before that time, at most
//            max_age_s old, carried to it by its velocity and acceleration
//            (x + v dt + a dt²/2): points at a lower rate than the loop, or
//            one tick late, give a smooth reference;
//   stale    the newest point is older than max_age_s, or none came yet: the
//            declared rule applies, and the tick is counted (stale_ticks,
//            missing_ticks before the first point):
//              hold_last       the last point's position, at rest; the
//                              measured value (at rest) before any point;
//              decay_to_state  from the last point's position to the
//                              measured value, with time constant decay_s;
//              fall_back       at() throws wbi::Error naming the input: the
//                              host falls back to hold and says why.
// Points may come ahead of time (a generator publishing the next tick's
// point): they wait in the input until the robot's time reaches them. Points
// come in time order from one publisher; a point older than the newest, or a
// robot time before the held point, is a restart (a new simulation starts at
// t = 0, a generator restarted): what was held and queued is dropped.
#pragma once

#include <array>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>

#include <Eigen/Core>

namespace wbi::controllers {

// Values per point at most (idl/references.idl's MAX_REFERENCE_VALUES).
inline constexpr int kMaxReferenceValues = 64;

enum class StaleRule { hold_last, decay_to_state, fall_back };
const char* to_string(StaleRule rule);

struct ReferenceSpec {
  std::string name{};  // the topic's last part: wbi/<robot>/references/<controller>/<name>
  std::string unit{};  // of position, e.g. "m"
  std::string help{};  // one line
  int size = 1;        // values per point (1..kMaxReferenceValues)
  double max_age_s = 0.05;
  StaleRule rule = StaleRule::hold_last;
  double decay_s = 0.5;  // decay_to_state's time constant
};

struct TrajectoryPoint {
  std::int64_t stamp_ns = 0;  // the robot time it is for (the state's source stamps)
  std::uint64_t seq = 0;
  int size = 0;
  std::array<double, kMaxReferenceValues> position{}, velocity{}, acceleration{};
};

enum class ReferenceStatus { fresh, stale, missing };

class ReferenceInput {
 public:
  // Points that may wait for their time at once; a point beyond overwrites
  // the oldest (counted).
  static constexpr std::size_t kCapacity = 64;

  // owner: "<controller>/<input>" for error texts.
  ReferenceInput(std::string owner, ReferenceSpec spec);
  ReferenceInput(const ReferenceInput&) = delete;
  ReferenceInput& operator=(const ReferenceInput&) = delete;

  const ReferenceSpec& spec() const { return spec_; }
  const std::string& owner() const { return owner_; }

  // Any thread (the DDS reader's). Returns false when the point is refused: a
  // size other than the declared one (counted as malformed).
  bool push(const TrajectoryPoint& point);

  // Loop thread, once per tick: the reference at time_ns (the stamp of the
  // state the controller answers). `measured()`: the
  // controlled quantity now (the stale rules' target; called only when a
  // rule applies). No allocation; it waits at most for a push() in
  // progress (one point's copy).
  template <class Measured>
  ReferenceStatus at(std::int64_t time_ns, Measured&& measured) {
    if (follow(time_ns)) {
      return ReferenceStatus::fresh;
    }
    apply_rule(time_ns, measured());
    return has_current_ ? ReferenceStatus::stale : ReferenceStatus::missing;
  }
  const Eigen::VectorXd& position() const { return position_; }
  const Eigen::VectorXd& velocity() const { return velocity_; }
  const Eigen::VectorXd& acceleration() const { return acceleration_; }

  // Lockstep runs, whose references come from a generator in step with the
  // robot: at() first waits (at most wait_ns) for a point for its time or
  // later, once the input has had a point (a late one is counted: late()).
  // After a wait timed out, no tick waits until the next point comes: a
  // generator that died costs one wait, not one per tick.
  // 0 (default): never waits. Set before the loop starts.
  void set_wait(std::int64_t wait_ns) { wait_ns_ = wait_ns; }
  // Loop thread: waits (at most timeout_ns) until a point for time_ns or later
  // has come; true when it has (the host's first tick: a generator's start).
  // A timeout is counted in late().
  bool wait_for(std::int64_t time_ns, std::int64_t timeout_ns);
  // Any thread, without waiting: whether at(time_ns) would find what it waits
  // for, so would not wait (first: whether wait_for(time_ns, …) would not).
  bool ready_for(std::int64_t time_ns, bool first) const;

  // A new activation: the held point and the counts of this run are kept, the
  // stale episode is not.
  void reset_episode() { stale_since_ns_ = -1; }

  std::uint64_t received() const;
  std::uint64_t malformed() const;    // refused: the wrong size
  std::uint64_t overwritten() const;  // the oldest waiting point, when full
  std::uint64_t late() const;         // waits that timed out
  std::uint64_t restarts() const;     // points that went back in time
  std::uint64_t carried_ticks() const { return carried_ticks_; }    // fresh, between points
  std::uint64_t stale_ticks() const { return stale_ticks_; }        // after a point
  std::uint64_t missing_ticks() const { return missing_ticks_; }    // before the first
  std::uint64_t stale_episodes() const { return stale_episodes_; }  // fresh → stale
  // Every count above in one line, "reference <owner>: N points (…); ticks: …",
  // for the host's shutdown.
  std::string summary() const;

 private:
  void take_due(std::int64_t time_ns);  // moves the points due at time_ns into current_
  bool follow(std::int64_t time_ns);    // true: fresh (position_… set)
  void wait_if_fed(std::int64_t time_ns);
  void apply_rule(std::int64_t time_ns, const Eigen::Ref<const Eigen::VectorXd>& measured);

  const std::string owner_;
  const ReferenceSpec spec_;

  mutable std::mutex mutex_;  // guards the queue and counts below
  std::condition_variable arrived_;
  std::array<TrajectoryPoint, kCapacity> queue_;  // ring, in arrival order
  std::size_t head_ = 0, count_ = 0;
  std::int64_t newest_stamp_ns_ = 0;
  std::uint64_t received_ = 0, malformed_ = 0, overwritten_ = 0, late_ = 0, restarts_ = 0;
  bool restarted_ = false;       // for the loop thread: drop the held point
  bool wait_timed_out_ = false;  // no waiting until the next point (set_wait)
  std::int64_t wait_ns_ = 0;

  // Loop thread only.
  TrajectoryPoint current_;  // the newest point due
  bool has_current_ = false;
  std::int64_t stale_since_ns_ = -1;
  std::uint64_t carried_ticks_ = 0, stale_ticks_ = 0, missing_ticks_ = 0, stale_episodes_ = 0;
  Eigen::VectorXd position_, velocity_, acceleration_;
};

}  // namespace wbi::controllers
