#include "dynamic_printer.hpp"

#include <charconv>
#include <iomanip>
#include <map>
#include <string>

#include <fastrtps/types/DynamicTypeMember.h>
#include <fastrtps/types/MemberDescriptor.h>
#include <fastrtps/types/TypeDescriptor.h>

namespace wbi::dds::detail {

namespace types = eprosima::fastrtps::types;

namespace {

types::DynamicType_ptr resolve_alias(types::DynamicType_ptr type) {
  while (type && type->get_kind() == types::TK_ALIAS) {
    type = type->get_descriptor()->get_base_type();
  }
  return type;
}

// The shortest text that reads back as the same value.
template <class Float>
std::string shortest(Float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

bool is_scalar(types::TypeKind kind) {
  return kind != types::TK_STRUCTURE && kind != types::TK_SEQUENCE && kind != types::TK_ARRAY;
}

// Prints the scalar `id` of `data` (a member id, or an element index).
void print_scalar(std::ostream& out, types::DynamicData& data, types::TypeKind kind,
                  types::MemberId id) {
  switch (kind) {
    case types::TK_BOOLEAN:
      out << (data.get_bool_value(id) ? "true" : "false");
      break;
    case types::TK_BYTE:
      out << static_cast<int>(data.get_byte_value(id));
      break;
    case types::TK_CHAR8:
      out << data.get_char8_value(id);
      break;
    case types::TK_INT16:
      out << data.get_int16_value(id);
      break;
    case types::TK_UINT16:
      out << data.get_uint16_value(id);
      break;
    case types::TK_INT32:
      out << data.get_int32_value(id);
      break;
    case types::TK_UINT32:
      out << data.get_uint32_value(id);
      break;
    case types::TK_INT64:
      out << data.get_int64_value(id);
      break;
    case types::TK_UINT64:
      out << data.get_uint64_value(id);
      break;
    case types::TK_FLOAT32:
      out << shortest(data.get_float32_value(id));
      break;
    case types::TK_FLOAT64:
      out << shortest(data.get_float64_value(id));
      break;
    case types::TK_STRING8:
      out << std::quoted(data.get_string_value(id));
      break;
    case types::TK_ENUM: {
      std::string name;
      data.get_enum_value(name, id);
      out << name;
      break;
    }
    default:
      out << "<unsupported kind " << static_cast<int>(kind) << ">";
      break;
  }
}

void print_value(std::ostream& out, types::DynamicData& parent, types::MemberId id,
                 const types::DynamicType_ptr& declared_type, int indent);

// Sequences and arrays: scalars inline as [a, b, c]; structures as a YAML list.
void print_collection(std::ostream& out, types::DynamicData& data,
                      const types::DynamicType_ptr& type, int indent) {
  const auto element_type = resolve_alias(type->get_descriptor()->get_element_type());
  const std::uint32_t count = data.get_item_count();
  if (is_scalar(element_type->get_kind())) {
    out << "[";
    for (std::uint32_t i = 0; i < count; ++i) {
      out << (i == 0 ? "" : ", ");
      print_scalar(out, data, element_type->get_kind(), i);
    }
    out << "]\n";
    return;
  }
  if (count == 0) {
    out << "[]\n";
    return;
  }
  out << "\n";
  for (std::uint32_t i = 0; i < count; ++i) {
    out << std::string(static_cast<std::size_t>(indent), ' ') << "-";
    print_value(out, data, i, element_type, indent + 2);
  }
}

void print_value(std::ostream& out, types::DynamicData& parent, types::MemberId id,
                 const types::DynamicType_ptr& declared_type, int indent) {
  const auto type = resolve_alias(declared_type);
  if (is_scalar(type->get_kind())) {
    out << " ";
    print_scalar(out, parent, type->get_kind(), id);
    out << "\n";
    return;
  }
  types::DynamicData* child = parent.loan_value(id);
  if (child == nullptr) {
    out << " <unreadable>\n";
    return;
  }
  if (type->get_kind() == types::TK_STRUCTURE) {
    out << "\n";
    print_yaml(out, *child, type, indent);
  } else {
    out << " ";
    print_collection(out, *child, type, indent);
  }
  parent.return_loaned_value(child);
}

}  // namespace

void print_yaml(std::ostream& out, types::DynamicData& data, const types::DynamicType_ptr& type,
                int indent) {
  std::map<types::MemberId, types::DynamicTypeMember*> members;
  type->get_all_members(members);
  for (const auto& [id, member] : members) {
    types::MemberDescriptor descriptor;
    member->get_descriptor(&descriptor);
    out << std::string(static_cast<std::size_t>(indent), ' ') << member->get_name() << ":";
    print_value(out, data, id, descriptor.get_type(), indent + 2);
  }
}

}  // namespace wbi::dds::detail
