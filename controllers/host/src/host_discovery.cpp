#include "wbi/controllers/host_discovery.hpp"

#include <algorithm>
#include <optional>
#include <string_view>

#include <wbi/dds/rpc.hpp>
#include <wbi/dds/topics.hpp>

namespace wbi::controllers {

namespace {

// "wbi/<robot>/controllers/reply" -> "<robot>"; "" for any other topic. The
// name's shape comes from the functions that name it, with a placeholder robot.
std::string robot_of_reply_topic(std::string_view topic) {
  static const std::string kPlaceholder = "\x01";
  static const std::string kShape =
      dds::topics::service_reply(dds::topics::controller_service(kPlaceholder));
  static const std::size_t kAt = kShape.find(kPlaceholder);
  const std::string_view prefix = std::string_view(kShape).substr(0, kAt);
  const std::string_view suffix = std::string_view(kShape).substr(kAt + kPlaceholder.size());
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
