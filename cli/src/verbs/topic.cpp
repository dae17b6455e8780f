// `wbi topic list|echo`: what is on the DDS domain, for debugging.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <iostream>
#include <mutex>
#include <string>
#include <thread>

#include <wbi/dds/participant.hpp>
#include <wbi/dds/raw_subscriber.hpp>
#include <wbi/dds/topic_echo.hpp>

#include "../join_options.hpp"
#include "../options.hpp"
#include "../subcommands.hpp"
#include "verbs.hpp"

namespace wbi::cli {

namespace {

using std::chrono::duration;
using std::chrono::duration_cast;
using std::chrono::nanoseconds;

constexpr const char* kEchoExample = "wbi topic echo wbi/arm/state --count 1";
constexpr const char* kHzExample = "wbi topic hz wbi/arm/sensors --duration 3";

nanoseconds seconds(double s) { return duration_cast<nanoseconds>(duration<double>(s)); }

// On a secured deployment, the topic verbs look as the observer (subscribe only).
dds::ParticipantOptions participant_options(const Options& options) {
  return join_options(options, "wbi topic", "observer");
}

int run_list(Args args) {
  Options options("wbi topic list [options]",
                  "Lists the topics that other participants on the domain publish or subscribe,\n"
                  "with their type and the number of writers and readers.");
  add_join_options(options, true, "observer");
  options.option("wait", "SECONDS", "how long to listen to discovery", "1.0");
  options.example("wbi topic list", "what the processes on the domain publish and subscribe");
  options.example("WBI_DOMAIN_ID=5 wbi topic list --wait 3",
                  "on domain 5 (as --domain 5), listening to discovery longer");
  if (!options.parse(args)) {
    return kExitOk;
  }
  dds::Participant participant(participant_options(options));
  std::this_thread::sleep_for(
      seconds(options.get_double("wait")));  // discovery has no "done" event
  for (const auto& topic : participant.discovered_topics()) {
    std::cout << topic.name << "  [" << topic.type << "]  writers: " << topic.writers
              << "  readers: " << topic.readers << "\n";
  }
  return kExitOk;
}

std::atomic<bool> interrupted{false};
extern "C" void on_echo_interrupt(int /*signal*/) { interrupted = true; }

void stop_on_signals() {
  std::signal(SIGINT, on_echo_interrupt);
  std::signal(SIGTERM, on_echo_interrupt);
}

dds::TopicInfo find_topic(dds::Participant& participant, const std::string& name,
                          const Options& options) {
  auto topic = participant.wait_for_topic(name, seconds(options.get_double("timeout")));
  if (!topic) {
    throw std::runtime_error("topic '" + name + "' not found on domain " +
                             std::to_string(participant.domain_id()) + " within " +
                             options.get("timeout") + " s");
  }
  return *topic;
}

int run_echo(Args args) {
  Options options("wbi topic echo TOPIC [options]",
                  "Prints every sample of TOPIC as YAML, separated by '---'. The topic's type\n"
                  "is learnt from discovery; it must be a wbi message type.");
  options.positional("TOPIC", "topic name, e.g. wbi/arm/sensors");
  add_join_options(options, true, "observer");
  options.option("count", "N", "exit after N samples (0: until Ctrl-C)", "0");
  options.option("timeout", "SECONDS", "give up when the topic is not found within this time", "5");
  options.example(kEchoExample, "one estimate of the arm's state (wbi launch deploy/demo.yaml)");
  options.example("wbi topic echo wbi/events", "every event, until Ctrl-C");
  if (!options.parse(args)) {
    return kExitOk;
  }
  const std::string topic_name = options.get("TOPIC");
  const long wanted = options.get_int("count");
  if (wanted < 0) {
    throw UsageError("--count must be >= 0");
  }
  dds::Participant participant(participant_options(options));
  const auto topic = find_topic(participant, topic_name, options);
  std::mutex mutex;
  std::condition_variable done;
  long printed = 0;
  dds::TopicEcho echo(participant, topic, [&](const std::string& yaml) {
    std::lock_guard lock(mutex);
    if (wanted != 0 && printed >= wanted) {
      return;
    }
    std::cout << yaml << "---\n" << std::flush;
    ++printed;
    done.notify_all();
  });
  stop_on_signals();
  std::unique_lock lock(mutex);
  while (!interrupted && (wanted == 0 || printed < wanted)) {
    done.wait_for(lock, std::chrono::milliseconds(100));  // also polls the signal flag
  }
  return interrupted ? kExitInterrupted : kExitOk;
}

// Rate statistics of one reporting window, from arrival times.
struct RateWindow {
  std::uint64_t count = 0;
  std::uint64_t bytes = 0;
  std::int64_t first_ns = 0;
  std::int64_t last_ns = 0;
  double max_gap_s = 0.0;

  void add(std::int64_t received_ns, std::size_t size) {
    if (count > 0) {
      max_gap_s = std::max(max_gap_s, 1e-9 * static_cast<double>(received_ns - last_ns));
    } else {
      first_ns = received_ns;
    }
    last_ns = received_ns;
    ++count;
    bytes += size;
  }
};

int run_hz(Args args) {
  Options options("wbi topic hz TOPIC [options]",
                  "Prints the rate at which samples of TOPIC arrive, once per window:\n"
                  "rate, largest gap between samples, bandwidth. Works for any type.");
  options.positional("TOPIC", "topic name, e.g. wbi/arm/sensors");
  add_join_options(options, true, "observer");
  options.option("window", "SECONDS", "length of a reporting window", "1.0");
  options.option("duration", "SECONDS", "stop after this long (0: until Ctrl-C)", "0");
  options.option("timeout", "SECONDS", "give up when the topic is not found within this time", "5");
  options.example(kHzExample, "the rate of the arm's sensors, for 3 s");
  if (!options.parse(args)) {
    return kExitOk;
  }
  const double window_s = options.get_double("window");
  const double duration_s = options.get_double("duration");
  if (window_s <= 0.0 || duration_s < 0.0) {
    throw UsageError("--window must be > 0 and --duration >= 0");
  }
  dds::Participant participant(participant_options(options));
  const auto topic = find_topic(participant, options.get("TOPIC"), options);
  std::mutex mutex;
  RateWindow window;
  dds::RawSubscriber subscriber(participant, topic, [&](const dds::RawSample& sample) {
    std::lock_guard lock(mutex);
    window.add(sample.received_ns, sample.cdr.size());
  });
  stop_on_signals();
  const auto start = std::chrono::steady_clock::now();
  auto next_report = start;
  while (!interrupted) {
    next_report += seconds(window_s);
    std::this_thread::sleep_until(next_report);  // a reporting period, not a synchronisation
    RateWindow done;
    {
      std::lock_guard lock(mutex);
      std::swap(done, window);
    }
    const double span_s = 1e-9 * static_cast<double>(done.last_ns - done.first_ns);
    const double rate =
        done.count > 1 && span_s > 0 ? static_cast<double>(done.count - 1) / span_s : 0.0;
    std::cout << "rate: " << rate << " Hz  samples: " << done.count
              << "  max gap: " << 1e3 * done.max_gap_s
              << " ms  bandwidth: " << static_cast<double>(done.bytes) / window_s / 1024.0
              << " KiB/s" << std::endl;
    if (duration_s > 0 && std::chrono::steady_clock::now() - start >= seconds(duration_s)) {
      break;
    }
  }
  return interrupted ? kExitInterrupted : kExitOk;
}

}  // namespace

int run_topic(Args args) {
  return run_subcommand("topic", args,
                        {
                            {"list", "list the topics on the domain", "wbi topic list", run_list},
                            {"echo", "print the samples of a topic", kEchoExample, run_echo},
                            {"hz", "measure the rate of a topic", kHzExample, run_hz},
                        });
}

}  // namespace wbi::cli
