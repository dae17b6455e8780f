// Internal: a QoS file given by a deploy file (or WBI_QOS_FILE) overrides the
// built-in profiles it names; the built-in ones fill in the rest. So a file
// that changes one profile holds only that profile, not a copy of them all.
#pragma once

#include <set>
#include <string>
#include <string_view>

namespace wbi::dds::detail {

// The profile names an XML text defines (its profile_name="..." attributes).
std::set<std::string> qos_profile_names(std::string_view xml);

// xml (wbi's built-in profiles) without the <data_writer> and <data_reader>
// elements whose profile_name is in names.
std::string qos_profiles_without(std::string_view xml, const std::set<std::string>& names);

}  // namespace wbi::dds::detail
