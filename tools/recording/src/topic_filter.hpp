// Which topics a recorder or player handles: names that fully match one of
// the include regexes (ECMAScript; all names when there are none) and not the
// exclude one.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace wbi::recording {

class TopicFilter {
 public:
  // Throws std::invalid_argument naming the pattern when one is not a valid regex.
  TopicFilter(const std::vector<std::string>& include, const std::string& exclude);
  ~TopicFilter();
  TopicFilter(const TopicFilter&) = delete;
  TopicFilter& operator=(const TopicFilter&) = delete;

  bool accepts(const std::string& topic) const;

 private:
  struct Patterns;  // the compiled regexes: <regex> stays in topic_filter.cpp
  std::unique_ptr<Patterns> patterns_;
};

}  // namespace wbi::recording
