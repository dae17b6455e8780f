// Little-endian encoding into a growable byte buffer, and bounds-checked
// decoding of a record's fields. Internal to wbi::mcap.
#pragma once

#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "wbi/mcap/format.hpp"

namespace wbi::mcap::detail {

template <typename T>
inline void store_le(std::uint8_t* out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out[i] = static_cast<std::uint8_t>(value >> (8 * i));
  }
}

template <typename T>
inline T load_le(const std::uint8_t* in) {
  T value = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    value = static_cast<T>(value | (static_cast<T>(in[i]) << (8 * i)));
  }
  return value;
}

// A byte vector that keeps its capacity across clear() and does not zero what
// it appends (std::vector::resize would).
class ByteBuffer {
 public:
  const std::uint8_t* data() const { return data_.get(); }
  std::uint8_t* data() { return data_.get(); }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  std::span<const std::uint8_t> span() const { return {data_.get(), size_}; }
  void clear() { size_ = 0; }

  void reserve(std::size_t capacity) {
    if (capacity <= capacity_) {
      return;
    }
    std::size_t grown = capacity_ == 0 ? 256 : capacity_;
    while (grown < capacity) {
      grown *= 2;
    }
    auto bigger = std::make_unique_for_overwrite<std::uint8_t[]>(grown);
    if (size_ > 0) {
      std::memcpy(bigger.get(), data_.get(), size_);
    }
    data_ = std::move(bigger);
    capacity_ = grown;
  }
  // Makes room for n more bytes and returns where they go; commit with grow().
  std::uint8_t* tail(std::size_t n) {
    reserve(size_ + n);
    return data_.get() + size_;
  }
  void grow(std::size_t n) { size_ += n; }
  void resize(std::size_t n) {
    reserve(n);
    size_ = n;
  }

  void append(const void* bytes, std::size_t n) {
    if (n > 0) {
      std::memcpy(tail(n), bytes, n);
      size_ += n;
    }
  }
  template <typename T>
  void put(T value) {
    store_le(tail(sizeof(T)), value);
    size_ += sizeof(T);
  }
  void put_string(std::string_view text) {
    put(static_cast<std::uint32_t>(text.size()));
    append(text.data(), text.size());
  }
  void put_bytes32(std::span<const std::uint8_t> bytes) {
    put(static_cast<std::uint32_t>(bytes.size()));
    append(bytes.data(), bytes.size());
  }
  void put_key_values(const KeyValues& entries) {
    std::uint64_t length = 0;
    for (const auto& [key, value] : entries) {
      length += 8 + key.size() + value.size();
    }
    put(static_cast<std::uint32_t>(length));
    for (const auto& [key, value] : entries) {
      put_string(key);
      put_string(value);
    }
  }
  // Record framing: opcode and a length patched by end_record().
  std::size_t begin_record(Opcode opcode) {
    put(static_cast<std::uint8_t>(opcode));
    const std::size_t start = size_;
    put(std::uint64_t{0});
    return start;
  }
  void end_record(std::size_t length_at) {
    store_le(data_.get() + length_at, static_cast<std::uint64_t>(size_ - length_at - 8));
  }

 private:
  std::unique_ptr<std::uint8_t[]> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

// A field that does not fit in its record. at: offset within the parsed bytes.
class ParseError : public std::runtime_error {
 public:
  ParseError(std::size_t at, const std::string& what) : std::runtime_error(what), at_(at) {}
  std::size_t at() const { return at_; }

 private:
  std::size_t at_;
};

// Reads the fields of one record's content, each checked against its end.
class FieldReader {
 public:
  explicit FieldReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  std::size_t position() const { return position_; }
  std::size_t remaining() const { return bytes_.size() - position_; }

  template <typename T>
  T get(const char* field) {
    need(sizeof(T), field);
    const T value = load_le<T>(bytes_.data() + position_);
    position_ += sizeof(T);
    return value;
  }
  std::span<const std::uint8_t> bytes(std::uint64_t n, const char* field) {
    need(n, field);
    const auto out = bytes_.subspan(position_, static_cast<std::size_t>(n));
    position_ += static_cast<std::size_t>(n);
    return out;
  }
  // A uint32 length and that many bytes; an overrun is reported at the length.
  std::span<const std::uint8_t> bytes32(const char* field) {
    const std::size_t start = position_;
    const auto n = get<std::uint32_t>(field);
    need(n, field, start);
    return bytes(n, field);
  }
  std::string string(const char* field) {
    const auto raw = bytes32(field);
    return {reinterpret_cast<const char*>(raw.data()), raw.size()};
  }
  KeyValues key_values(const char* field) {
    FieldReader entries(bytes32(field));
    KeyValues out;
    while (entries.remaining() > 0) {
      std::string key = entries.string(field);
      out[std::move(key)] = entries.string(field);
    }
    return out;
  }
  std::map<std::uint16_t, std::uint64_t> id_counts(const char* field) {
    FieldReader entries(bytes32(field));
    std::map<std::uint16_t, std::uint64_t> out;
    while (entries.remaining() > 0) {
      const auto key = entries.get<std::uint16_t>(field);
      out[key] = entries.get<std::uint64_t>(field);
    }
    return out;
  }
  std::span<const std::uint8_t> rest() {
    const auto out = bytes_.subspan(position_);
    position_ = bytes_.size();
    return out;
  }

 private:
  void need(std::uint64_t n, const char* field) const { need(n, field, position_); }
  void need(std::uint64_t n, const char* field, std::size_t start) const {
    if (n > remaining()) {
      throw ParseError(start, std::string("field '") + field + "' needs " + std::to_string(n) +
                                  " bytes but only " + std::to_string(remaining()) +
                                  " remain in the record");
    }
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
};

}  // namespace wbi::mcap::detail
