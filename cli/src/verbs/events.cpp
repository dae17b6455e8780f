// `wbi events`: what happened in a run, live (wbi/events, docs/events.md).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <iostream>
#include <mutex>
#include <string>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/subscriber.hpp>
#include <wbi/dds/topics.hpp>

#include "../event_lines.hpp"
#include "../join_options.hpp"
#include "../options.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

std::atomic<bool> interrupted{false};
extern "C" void on_events_interrupt(int /*signal*/) { interrupted = true; }

EventFilter read_filter(const Options& options) {
  EventFilter filter;
  filter.robot = options.get_optional("robot");
  if (const auto severity = options.get_optional("severity")) {
    filter.min_severity = parse_event_severity(*severity);
  }
  if (const auto kinds = options.get_optional("kind")) {
    filter.kinds = parse_event_kinds(*kinds);
  }
  return filter;
}

}  // namespace

int run_events(Args args) {
  Options options(
      "wbi events [--robot NAME] [--severity MIN] [--kind KIND[,KIND...]] [--json] [options]",
      "Prints the events of every component and launcher on the domain (wbi/events) as\n"
      "they happen, one line each: time, severity, participant:source, kind, robot,\n"
      "[subject] text. Events sent before it started are printed too (each sender\n"
      "keeps its last 64). Kinds: PROCESS_STARTED, PROCESS_EXITED, PROCESS_RESPAWNED,\n"
      "PROCESS_HUNG, LIFECYCLE, LOOP_STALL, WATCHDOG_TRIP, CLAIM_CHANGED, CLAIM_FORCED,\n"
      "COMMANDS_REJECTED, PRODUCER_RESTARTED, DIVERGENCE, CONTROLLER_SWITCHED,\n"
      "CONTROLLER_FALLBACK, PARAMETER_CHANGED, REFERENCE_STALE (docs/events.md).");
  options.option("robot", "NAME", "only the events about this robot");
  options.option("severity", "MIN",
                 "only events this serious or more: debug, info, warning, error, fatal");
  options.option("kind", "KIND[,KIND...]", "only these kinds (any case)");
  options.flag("json", "one JSON object per line instead");
  options.option("count", "N", "exit after N matching events (0: until Ctrl-C)", "0");
  options.option("timeout", "SECONDS",
                 "stop after this long (0: never); with --count, exit 1 when fewer came", "0");
  add_join_options(options, true, "observer");
  options.example("wbi events", "everything that happens on the domain, until Ctrl-C");
  options.example("wbi events --robot arm --severity warning",
                  "the arm's warnings, errors and fatal events");
  options.example("wbi events --kind CONTROLLER_SWITCHED --count 1 --timeout 60",
                  "wait up to a minute for a controller switch (exit 1 if none)");
  if (!options.parse(args)) {
    return kExitOk;
  }
  const EventFilter filter = read_filter(options);
  const bool json = options.has("json");
  const long wanted = options.get_int("count");
  const double timeout_s = options.get_double("timeout");
  if (wanted < 0 || !(timeout_s >= 0.0)) {
    throw UsageError("--count must be >= 0 and --timeout >= 0");
  }

  dds::Participant participant(join_options(options, "wbi events", "observer"));
  std::mutex mutex;
  std::condition_variable printed_one;
  long printed = 0;
  dds::Subscriber<msg::Event> events(
      participant, dds::topics::kEvents, dds::qos::kEvents,
      [&](const msg::Event& event, const dds::detail::SampleInfo&) {
        std::lock_guard lock(mutex);
        if ((wanted != 0 && printed >= wanted) || !filter.matches(event)) {
          return;
        }
        std::cout << (json ? json_line(event) : human_line(event)) << std::endl;
        ++printed;
        printed_one.notify_all();
      });
  std::signal(SIGINT, on_events_interrupt);
  std::signal(SIGTERM, on_events_interrupt);
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(timeout_s));
  std::unique_lock lock(mutex);
  while (!interrupted && (wanted == 0 || printed < wanted)) {
    if (timeout_s > 0.0 && std::chrono::steady_clock::now() >= deadline) {
      if (wanted == 0) {
        return kExitOk;
      }
      std::cerr << "wbi events: " << printed << " of " << wanted << " event(s) within "
                << options.get("timeout") << " s\n";
      return kExitError;
    }
    printed_one.wait_for(lock, std::chrono::milliseconds(100));  // also polls the signal flag
  }
  return interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace wbi::cli
