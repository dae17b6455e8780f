// Internal: prints a Fast DDS DynamicData sample as YAML.
#pragma once

#include <ostream>

#include <fastrtps/types/DynamicData.h>
#include <fastrtps/types/DynamicType.h>

namespace wbi::dds::detail {

// Prints the members of a structure, one per line, nested with two spaces.
void print_yaml(std::ostream& out, eprosima::fastrtps::types::DynamicData& data,
                const eprosima::fastrtps::types::DynamicType_ptr& type, int indent = 0);

}  // namespace wbi::dds::detail
