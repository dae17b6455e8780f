// Several names given as one, joined by '+': a foot on two F/T sensors
// ("l_foot_front_ft+l_foot_rear_ft"), a foot's contact links. One spelling for
// the estimator's and the balancer's parameters.
#pragma once

#include <string>
#include <vector>

namespace wbi {

// "a,b,c" split at `separator` → {a, b, c}; "a" → {a}; "" → {}. Empty parts
// ("a,,b") are kept, so that the caller names them as unknown names.
inline std::vector<std::string> split_names(const std::string& joined, char separator) {
  std::vector<std::string> names;
  if (joined.empty()) {
    return names;
  }
  std::size_t begin = 0;
  for (auto at = joined.find(separator); at != std::string::npos;
       at = joined.find(separator, begin)) {
    names.push_back(joined.substr(begin, at - begin));
    begin = at + 1;
  }
  names.push_back(joined.substr(begin));
  return names;
}

// "a+b+c" → {a, b, c}.
inline std::vector<std::string> split_joined_names(const std::string& joined) {
  return split_names(joined, '+');
}

}  // namespace wbi
