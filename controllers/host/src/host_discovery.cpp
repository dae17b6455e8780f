#include "wbi/controllers/host_discovery.hpp"

#include <algorithm>
#include <optional>
#include <string_view>

namespace wbi::controllers {

namespace {

// "wbi/<robot>/controllers/reply" (topics::service_reply(topics::controller_service(robot)))
// -> "<robot>"; "" for any other topic.
std::string robot_of_reply_topic(std::string_view topic) {
  constexpr std::string_view prefix = "wbi/";
  constexpr std::string_view suffix = "/controllers/reply";
  if (topic.size() <= prefix.size() + suffix.size() || !topic.starts_with(prefix) ||
      !topic.ends_with(suffix)) {
    return "";
  }
  return std::string(topic.substr(prefix.size(), topic.size() - prefix.size() - suffix.size()));
}

}  // namespace

std::vector<std::string> controller_hosts(const dds::Participant& participant) {
  std::vector<std::string> robots;
  for (const auto& topic : participant.discovered_topics()) {
    const std::string robot = robot_of_reply_topic(topic.name);
    if (robot.empty() || topic.writers == 0) {
      continue;
    }
    const auto writers = participant.publishers_of(topic.name);
    if (std::any_of(writers.begin(), writers.end(),
                    [&](const auto& writer) { return !participant.has_ended(writer); })) {
      robots.push_back(robot);
    }
  }
  return robots;  // discovered_topics() is sorted by name, and one reply topic per robot
}

std::vector<std::string> find_controller_hosts(const dds::Participant& participant,
                                               std::chrono::nanoseconds timeout,
                                               std::chrono::nanoseconds settle) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto deadline = start + timeout;
  std::optional<std::chrono::nanoseconds> quiet;  // set once a first host is known
  for (;;) {
    const auto seen = participant.discovered_topics();
    const auto hosts = controller_hosts(participant);
    const auto now = Clock::now();
    if (!hosts.empty() && !quiet) {
      // A loaded machine discovers slowly: as long again as the first host took.
      quiet = std::max<std::chrono::nanoseconds>(settle, now - start);
    }
    const auto left = deadline - now;
    if (left <= std::chrono::nanoseconds::zero()) {
      return hosts;
    }
    const bool changed = participant.wait_for_topics(
        [&](const std::vector<dds::TopicInfo>& topics) { return topics != seen; },
        quiet ? std::min<std::chrono::nanoseconds>(*quiet, left) : left);
    if (!changed) {
      return hosts;  // quiet after a first host, or `timeout` without any
    }
  }
}

}  // namespace wbi::controllers
