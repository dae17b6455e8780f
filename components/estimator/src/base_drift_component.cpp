// The `base_drift` component: how far a robot's base estimate (its state
// topic) drifts from the simulator's ground truth, tick by tick, matched by
// stamp. The estimator's world frame need not be the simulator's (a legged
// base starts at x = y = 0), so the offset of the first matched tick is taken
// off (that of the 100th matched tick: the first estimates settle): what
// remains is drift. Printed when it stops, e.g.
//   base estimate against the ground truth over 15000 ticks: horizontal drift
//   at the end 4.1 mm, largest 6.3 mm; height error rms 1.2 mm
// Parameters: robot (required). It reads; it publishes nothing.
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <mutex>

#include <wbi/msg/sensors.h>
#include <wbi/msg/state.h>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/estimator/estimator_component.hpp>
#include <wbi/msg/eigen.hpp>
#include <wbi/runtime/component.hpp>
#include <wbi/runtime/console_line.hpp>

namespace wbi::estimator {

namespace {

class BaseDrift final : public runtime::Component {
 public:
  void on_configure(const runtime::Parameters& parameters,
                    const runtime::ComponentContext& context) override {
    robot_ = parameters.require<std::string>("robot");
    auto& participant = *context.participant;
    estimates_ = std::make_unique<dds::Subscriber<wbi::msg::StateEstimate>>(
        participant, dds::topics::state(robot_), dds::qos::kStream,
        [this](const wbi::msg::StateEstimate& s, const dds::detail::SampleInfo&) {
          arrived(estimated_, truth_, s.header().stamp_ns(), s.base_pose().position());
        });
    truths_ = std::make_unique<dds::Subscriber<wbi::msg::GroundTruth>>(
        participant, dds::topics::ground_truth(robot_), dds::qos::kStream,
        [this](const wbi::msg::GroundTruth& g, const dds::detail::SampleInfo&) {
          arrived(truth_, estimated_, g.header().stamp_ns(), g.base_pose().position());
        });
  }

  void on_deactivate() override {
    std::lock_guard lock(mutex_);
    if (matched_ == 0) {
      runtime::print_line(stdout, "base estimate against the ground truth: no tick of robot '" +
                                      robot_ + "' had both");
      return;
    }
    char line[256];
    std::snprintf(line, sizeof line,
                  "base estimate against the ground truth over %llu ticks: horizontal drift at "
                  "the end %.1f mm, largest %.1f mm; height error rms %.1f mm",
                  static_cast<unsigned long long>(matched_), 1e3 * last_drift_,
                  1e3 * largest_drift_,
                  1e3 * std::sqrt(height_squared_ / static_cast<double>(matched_)));
    runtime::print_line(stdout, line);
  }

  void on_cleanup() override {
    estimates_.reset();
    truths_.reset();
  }

 private:
  // The last base positions of one stream, by stamp: the other stream's sample
  // of a tick may come first.
  struct Recent {
    static constexpr std::size_t kSize = 64;
    std::array<std::int64_t, kSize> stamp{};
    std::array<Eigen::Vector3d, kSize> position{};
    std::size_t next = 0;

    void add(std::int64_t s, const Eigen::Vector3d& p) {
      stamp[next] = s;
      position[next] = p;
      next = (next + 1) % kSize;
    }
    const Eigen::Vector3d* find(std::int64_t s) const {
      for (std::size_t i = 0; i < kSize; ++i) {
        if (stamp[i] == s) {
          return &position[i];
        }
      }
      return nullptr;
    }
  };

  // A sample of one stream: matched with the other's of the same stamp, else kept.
  void arrived(Recent& mine, const Recent& other, std::int64_t stamp,
               const wbi::msg::Vector3& position) {
    std::lock_guard lock(mutex_);
    const Eigen::Vector3d p = msg::to_eigen(position);
    const Eigen::Vector3d* q = other.find(stamp);
    if (q == nullptr) {
      mine.add(stamp, p);
      return;
    }
    const bool estimate_first = &mine == &estimated_;
    const Eigen::Vector3d error =
        estimate_first ? Eigen::Vector3d(p - *q) : Eigen::Vector3d(*q - p);
    // The offset from the tick kSettleTicks in: a legged estimate's first
    // ones still settle (its height starts at the soles' guess).
    if (++seen_ <= kSettleTicks) {
      offset_ = error;
      return;
    }
    ++matched_;
    const Eigen::Vector3d drift = error - offset_;
    last_drift_ = drift.head<2>().norm();
    largest_drift_ = std::max(largest_drift_, last_drift_);
    height_squared_ += drift.z() * drift.z();
  }

  std::string robot_;
  std::unique_ptr<dds::Subscriber<wbi::msg::StateEstimate>> estimates_;
  std::unique_ptr<dds::Subscriber<wbi::msg::GroundTruth>> truths_;
  std::mutex mutex_;
  Recent estimated_, truth_;
  Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();
  static constexpr std::uint64_t kSettleTicks = 100;
  std::uint64_t seen_ = 0, matched_ = 0;
  double last_drift_ = 0.0, largest_drift_ = 0.0, height_squared_ = 0.0;
};

}  // namespace

void register_base_drift(runtime::Registry& registry) {
  registry.add<BaseDrift>("base_drift",
                          "the base estimate's drift from the simulator's ground truth, printed "
                          "when it stops");
}

}  // namespace wbi::estimator
