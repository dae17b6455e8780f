#include "source_stamp.hpp"

#include <cctype>
#include <cstring>

namespace wbi::recording {

namespace {

void skip_space_and_comments(const std::string& text, std::size_t& pos) {
  while (pos < text.size()) {
    if (std::isspace(static_cast<unsigned char>(text[pos])) != 0) {
      ++pos;
    } else if (text.compare(pos, 2, "//") == 0) {
      pos = text.find('\n', pos);
      pos = pos == std::string::npos ? text.size() : pos;
    } else if (text.compare(pos, 2, "/*") == 0) {
      pos = text.find("*/", pos);
      pos = pos == std::string::npos ? text.size() : pos + 2;
    } else {
      return;
    }
  }
}

bool is_identifier_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}

// Reads the word at pos (identifier characters) and moves past it.
std::string next_word(const std::string& text, std::size_t& pos) {
  skip_space_and_comments(text, pos);
  const std::size_t start = pos;
  while (pos < text.size() && is_identifier_char(text[pos])) {
    ++pos;
  }
  return text.substr(start, pos - start);
}

}  // namespace

bool starts_with_header(const std::string& type_name, const std::string& idl_text) {
  const auto colon = type_name.rfind("::");
  const std::string name = colon == std::string::npos ? type_name : type_name.substr(colon + 2);
  std::size_t pos = 0;
  while ((pos = idl_text.find("struct", pos)) != std::string::npos) {
    const bool word_start = pos == 0 || !is_identifier_char(idl_text[pos - 1]);
    pos += 6;
    if (!word_start || pos >= idl_text.size() || is_identifier_char(idl_text[pos])) {
      continue;
    }
    if (next_word(idl_text, pos) != name) {
      continue;
    }
    skip_space_and_comments(idl_text, pos);
    if (pos >= idl_text.size() || idl_text[pos] != '{') {
      continue;  // a forward declaration
    }
    ++pos;
    return next_word(idl_text, pos) == "Header" && next_word(idl_text, pos) == "header";
  }
  return false;
}

namespace {

// The 8-byte member `index` after Header.robot: 0 stamp_ns, 1 seq.
std::optional<std::uint64_t> header_word(std::span<const std::uint8_t> cdr, std::size_t index) {
  constexpr std::size_t kEncapsulation = 4;
  if (cdr.size() < kEncapsulation + 4) {
    return std::nullopt;
  }
  // Encapsulation ids: 0/1 plain CDR (XCDR1, 8-byte alignment of int64),
  // 6/7 plain CDR2 (XCDR2, 4-byte alignment); odd: little endian.
  const std::uint8_t kind = cdr[1];
  if (cdr[0] != 0 || (kind != 0 && kind != 1 && kind != 6 && kind != 7)) {
    return std::nullopt;
  }
  const bool little = (kind & 1) != 0;
  const std::size_t int64_alignment = kind <= 1 ? 8 : 4;
  auto read = [&](std::size_t offset, std::size_t size) {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < size; ++i) {
      const std::uint64_t byte = cdr[kEncapsulation + offset + (little ? i : size - 1 - i)];
      value |= byte << (8 * i);
    }
    return value;
  };
  const std::size_t body = cdr.size() - kEncapsulation;
  const std::uint64_t name_length = read(0, 4);  // includes the terminating NUL
  std::size_t offset = 4 + name_length;
  offset = (offset + int64_alignment - 1) / int64_alignment * int64_alignment;
  offset += 8 * index;
  if (name_length > body || offset + 8 > body) {
    return std::nullopt;
  }
  return read(offset, 8);
}

}  // namespace

std::optional<std::int64_t> header_stamp_ns(std::span<const std::uint8_t> cdr) {
  const auto word = header_word(cdr, 0);
  return word ? std::optional<std::int64_t>(static_cast<std::int64_t>(*word)) : std::nullopt;
}

std::optional<std::uint64_t> header_seq(std::span<const std::uint8_t> cdr) {
  return header_word(cdr, 1);
}

}  // namespace wbi::recording
