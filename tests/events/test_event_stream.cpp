// The event stream in one process, over real DDS: an EventLog published by
// its EventPump reaches a wbi/events subscriber in order; a ComponentRunner
// says each lifecycle transition; a flood of one kind from several threads is
// held to the rate limit, and what it dropped is counted in the next event.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <yaml-cpp/yaml.h>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>
#include <wbi/msg/wire_vocabulary.hpp>
#include <wbi/runtime/clock.hpp>
#include <wbi/runtime/event_log.hpp>
#include <wbi/runtime/event_pump.hpp>
#include <wbi/runtime/runner.hpp>

#include "test_support.hpp"

namespace {

using namespace std::chrono_literals;
using wbi::EventKind;
using wbi::EventSeverity;

// Every event on wbi/events that one source sent, as it arrived.
class Received {
 public:
  Received(wbi::dds::Participant& participant, std::string source)
      : source_(std::move(source)),
        subscriber_(participant, wbi::dds::topics::kEvents, wbi::dds::qos::kEvents,
                    [this](const wbi::msg::Event& event, const wbi::dds::detail::SampleInfo&) {
                      if (event.source().to_string() == source_) {
                        std::lock_guard lock(mutex_);
                        events_.push_back(event);
                      }
                    }) {}

  std::vector<wbi::msg::Event> events() const {
    std::lock_guard lock(mutex_);
    return events_;
  }
  std::size_t count() const {
    std::lock_guard lock(mutex_);
    return events_.size();
  }
  bool wait_for(std::size_t count) const {
    return wbi::test::eventually([&] { return this->count() >= count; });
  }

 private:
  const std::string source_;
  mutable std::mutex mutex_;
  std::vector<wbi::msg::Event> events_;
  wbi::dds::Subscriber<wbi::msg::Event> subscriber_;
};

EventKind kind_of(const wbi::msg::Event& event) { return *wbi::msg::from_wire(event.kind()); }

TEST(EventStream, EventsArriveInOrderWithTheirFields) {
  wbi::dds::Participant participant("events_in_order");
  Received received(participant, "order_source");
  wbi::runtime::EventLog log;
  log.set_default_robot("arm");
  wbi::runtime::EventPump pump(participant, log, "order_source");
  const EventKind kinds[] = {EventKind::watchdog_trip, EventKind::claim_changed,
                             EventKind::loop_stall};
  constexpr int kEvents = 30;  // 10 of each kind: within each kind's burst
  for (int k = 0; k < kEvents; ++k) {
    ASSERT_TRUE(log.emit(EventSeverity::warning, kinds[k % 3], "event " + std::to_string(k),
                         k % 3 == 0 ? "joint_1,joint_2" : ""));
  }
  ASSERT_TRUE(received.wait_for(kEvents)) << received.count() << " of " << kEvents;
  const auto events = received.events();
  ASSERT_EQ(events.size(), static_cast<std::size_t>(kEvents));
  for (int k = 0; k < kEvents; ++k) {
    const auto& event = events[static_cast<std::size_t>(k)];
    EXPECT_EQ(event.text().to_string(), "event " + std::to_string(k));
    EXPECT_EQ(event.header().seq(), static_cast<std::uint64_t>(k));
    EXPECT_EQ(kind_of(event), kinds[k % 3]);
    EXPECT_EQ(event.header().robot().to_string(), "arm");
    EXPECT_EQ(event.participant().to_string(), "events_in_order");
    EXPECT_EQ(event.subject().to_string(), k % 3 == 0 ? "joint_1,joint_2" : "");
    EXPECT_EQ(event.suppressed(), 0u);
  }
  EXPECT_LT(events.front().header().stamp_ns(), events.back().header().stamp_ns());
}

class Probe final : public wbi::runtime::Component {
 public:
  void on_configure(const wbi::runtime::Parameters& parameters,
                    const wbi::runtime::ComponentContext&) override {
    parameters.require<std::string>("robot");
  }
  void on_activate() override {
    if (fail_activation) {
      throw std::runtime_error("no robot to talk to");
    }
  }
  bool fail_activation = false;
};

TEST(EventStream, ARunnerSaysEachLifecycleTransition) {
  wbi::dds::Participant participant("events_lifecycle");
  Received received(participant, "probe_1");
  wbi::runtime::SystemClock clock;
  auto probe = std::make_unique<Probe>();
  Probe& component = *probe;
  {
    wbi::runtime::ComponentRunner runner(std::move(probe),
                                         {"probe_1", "probe", &participant, &clock});
    runner.configure(wbi::runtime::Parameters(YAML::Load("{robot: arm}"), "test", "probe_1"));
    runner.activate();
    runner.deactivate();
    component.fail_activation = true;
    EXPECT_THROW(runner.activate(), wbi::runtime::TransitionError);
    runner.cleanup();
  }  // the runner's pump sends the rest: its shutdown
  ASSERT_TRUE(received.wait_for(6)) << received.count();
  const std::vector<std::pair<EventSeverity, std::string>> expected = {
      {EventSeverity::info, "UNCONFIGURED -> INACTIVE"},
      {EventSeverity::info, "INACTIVE -> ACTIVE"},
      {EventSeverity::info, "ACTIVE -> INACTIVE"},
      {EventSeverity::error, "activate failed: no robot to talk to"},
      {EventSeverity::info, "INACTIVE -> UNCONFIGURED"},
      {EventSeverity::info, "UNCONFIGURED -> FINALIZED"},
  };
  const auto events = received.events();
  ASSERT_EQ(events.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(kind_of(events[i]), EventKind::lifecycle);
    EXPECT_EQ(*wbi::msg::from_wire(events[i].severity()), expected[i].first) << i;
    EXPECT_EQ(events[i].text().to_string(), expected[i].second);
    EXPECT_EQ(events[i].header().robot().to_string(), "arm");
  }
}

// 1000 events of one kind from 4 threads at once: at most `burst` go out at
// once and `per_second` after that; the rest are counted, and the count
// travels with the next event of that kind that goes out.
TEST(EventStream, AFloodIsRateLimitedAndCounted) {
  wbi::dds::Participant participant("events_flood");
  Received received(participant, "flood_source");
  const wbi::runtime::EventRateLimit limit;  // the default: 2/s, burst 10
  wbi::runtime::EventLog log(limit);
  wbi::runtime::EventPump pump(participant, log, "flood_source");

  constexpr int kThreads = 4, kPerThread = 250;
  std::atomic<int> admitted{0};
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      for (int k = 0; k < kPerThread; ++k) {
        if (log.emit(EventSeverity::warning, EventKind::commands_rejected,
                     "flood " + std::to_string(t) + "." + std::to_string(k))) {
          ++admitted;
        }
      }
    });
  }
  for (auto& thread : threads) {
    thread.join();
  }
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int flood_admitted = admitted.load();
  EXPECT_GE(flood_admitted, 1);
  EXPECT_LE(flood_admitted, static_cast<int>(limit.burst + limit.per_second * elapsed_s) + 1)
      << "in " << elapsed_s << " s";

  // The next one admitted (once the bucket has refilled) carries the count.
  int attempts = kThreads * kPerThread;
  bool sent = false;
  ASSERT_TRUE(wbi::test::eventually(
      [&] {
        ++attempts;
        sent = log.emit(EventSeverity::warning, EventKind::commands_rejected, "after the flood");
        return sent;
      },
      3s));
  const std::size_t total = static_cast<std::size_t>(flood_admitted) + 1;
  ASSERT_TRUE(received.wait_for(total)) << received.count() << " of " << total;
  const auto events = received.events();
  ASSERT_EQ(events.size(), total);
  EXPECT_EQ(events.back().text().to_string(), "after the flood");
  EXPECT_GT(events.back().suppressed(), 0u);
  std::uint64_t accounted = 0;  // every attempt: sent, or counted in a later event
  for (const auto& event : events) {
    accounted += 1 + event.suppressed();
  }
  EXPECT_EQ(accounted, static_cast<std::uint64_t>(attempts));
  EXPECT_EQ(log.rate_limited(), static_cast<std::uint64_t>(attempts) - total);
  EXPECT_EQ(log.overflowed(), 0u);
}

}  // namespace
