#include "qos_layers.hpp"

namespace wbi::dds::detail {

namespace {
constexpr std::string_view kNameAttribute = "profile_name=\"";
}

std::set<std::string> qos_profile_names(std::string_view xml) {
  std::set<std::string> names;
  for (auto at = xml.find(kNameAttribute); at != std::string_view::npos;
       at = xml.find(kNameAttribute, at)) {
    at += kNameAttribute.size();
    const auto end = xml.find('"', at);
    if (end == std::string_view::npos) {
      break;
    }
    names.emplace(xml.substr(at, end - at));
    at = end;
  }
  return names;
}

std::string qos_profiles_without(std::string_view xml, const std::set<std::string>& names) {
  std::string out(xml);
  for (const std::string& name : names) {
    for (const std::string_view element : {"data_writer", "data_reader"}) {
      std::string open = "<";
      open.append(element).append(" ").append(kNameAttribute).append(name).append("\"");
      std::string close = "</";
      close.append(element).append(">");
      const auto begin = out.find(open);
      if (begin == std::string::npos) {
        continue;
      }
      const auto end = out.find(close, begin);
      if (end != std::string::npos) {
        out.erase(begin, end + close.size() - begin);
      }
    }
  }
  return out;
}

}  // namespace wbi::dds::detail
