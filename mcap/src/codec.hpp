// Chunk compression with zstd and LZ4 (frame format), contexts reused from
// chunk to chunk. Internal to wbi::mcap.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "byte_buffer.hpp"
#include "wbi/mcap/format.hpp"

namespace wbi::mcap::detail {

class Compressor {
 public:
  // level 0: the codec's fast default.
  Compressor(Compression compression, int level);
  ~Compressor();
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;

  // Replaces out's content with the compressed input. Throws std::runtime_error.
  void compress(std::span<const std::uint8_t> input, ByteBuffer& out);

 private:
  Compression compression_;
  int level_;
  void* context_ = nullptr;  // ZSTD_CCtx* or LZ4F_cctx*
};

// The uncompressed size that a zstd or LZ4 frame header declares, if it does
// (checked before allocating the output). Throws std::runtime_error when the
// input is not a frame of that compression.
std::optional<std::uint64_t> declared_size(std::string_view compression,
                                           std::span<const std::uint8_t> input);

class Decompressor {
 public:
  Decompressor() = default;
  ~Decompressor();
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;

  // Decompresses input (compression: "lz4" or "zstd", as in the file) into
  // exactly out.size() bytes. Throws std::runtime_error with the reason when
  // the compression is unknown, the input is malformed or its size differs.
  void decompress(std::string_view compression, std::span<const std::uint8_t> input,
                  std::span<std::uint8_t> out);

 private:
  void* zstd_ = nullptr;  // ZSTD_DCtx*
  void* lz4_ = nullptr;   // LZ4F_dctx*
};

}  // namespace wbi::mcap::detail
