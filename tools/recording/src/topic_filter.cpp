#include "topic_filter.hpp"

#include <stdexcept>

// GCC 12 reports a false "may be used uninitialized" inside libstdc++'s regex
// compiler when built with the sanitizers (-Werror makes it fatal); the
// warning is about the library's code, not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <regex>
#pragma GCC diagnostic pop

namespace wbi::recording {

struct TopicFilter::Patterns {
  std::vector<std::regex> include;
  std::vector<std::regex> exclude;  // at most one
};

namespace {

std::regex compile(const std::string& pattern) {
  try {
    return std::regex(pattern, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw std::invalid_argument("bad topic regex '" + pattern + "': " + e.what());
  }
}

}  // namespace

TopicFilter::TopicFilter(const std::vector<std::string>& include, const std::string& exclude)
    : patterns_(std::make_unique<Patterns>()) {
  for (const auto& pattern : include) {
    patterns_->include.push_back(compile(pattern));
  }
  if (!exclude.empty()) {
    patterns_->exclude.push_back(compile(exclude));
  }
}

TopicFilter::~TopicFilter() = default;

bool TopicFilter::accepts(const std::string& topic) const {
  bool included = patterns_->include.empty();
  for (const auto& pattern : patterns_->include) {
    included = included || std::regex_match(topic, pattern);
  }
  return included &&
         (patterns_->exclude.empty() || !std::regex_match(topic, patterns_->exclude.front()));
}

}  // namespace wbi::recording
