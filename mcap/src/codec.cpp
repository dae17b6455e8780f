#include "codec.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <optional>
#include <stdexcept>

namespace wbi::mcap::detail {

namespace {

constexpr int kZstdFastLevel = 1;

ZSTD_CCtx* zstd_cctx(void* context) { return static_cast<ZSTD_CCtx*>(context); }
LZ4F_cctx* lz4_cctx(void* context) { return static_cast<LZ4F_cctx*>(context); }

void check_lz4(std::size_t result, const char* what) {
  if (LZ4F_isError(result) != 0) {
    throw std::runtime_error(std::string(what) + ": " + LZ4F_getErrorName(result));
  }
}

LZ4F_preferences_t lz4_preferences(std::size_t content_size, int level) {
  LZ4F_preferences_t preferences{};
  // 64 KiB blocks: a decoder allocates two buffers of the block size per context.
  preferences.frameInfo.blockSizeID = LZ4F_max64KB;
  preferences.frameInfo.blockMode = LZ4F_blockIndependent;
  preferences.frameInfo.contentChecksumFlag = LZ4F_noContentChecksum;  // the chunk has its CRC
  preferences.frameInfo.contentSize = content_size;
  preferences.compressionLevel = level;
  return preferences;
}

}  // namespace

Compressor::Compressor(Compression compression, int level)
    : compression_(compression), level_(level) {
  switch (compression_) {
    case Compression::none:
      break;
    case Compression::zstd:
      context_ = ZSTD_createCCtx();
      if (context_ == nullptr) {
        throw std::runtime_error("cannot create a zstd compression context");
      }
      if (level_ == 0) {
        level_ = kZstdFastLevel;
      }
      break;
    case Compression::lz4: {
      LZ4F_cctx* cctx = nullptr;
      check_lz4(LZ4F_createCompressionContext(&cctx, LZ4F_VERSION), "lz4 context");
      context_ = cctx;
      break;
    }
  }
}

Compressor::~Compressor() {
  if (compression_ == Compression::zstd) {
    ZSTD_freeCCtx(zstd_cctx(context_));
  } else if (compression_ == Compression::lz4) {
    LZ4F_freeCompressionContext(lz4_cctx(context_));
  }
}

void Compressor::compress(std::span<const std::uint8_t> input, ByteBuffer& out) {
  out.clear();
  switch (compression_) {
    case Compression::none:
      out.append(input.data(), input.size());
      return;
    case Compression::zstd: {
      const std::size_t bound = ZSTD_compressBound(input.size());
      const std::size_t written = ZSTD_compressCCtx(zstd_cctx(context_), out.tail(bound), bound,
                                                    input.data(), input.size(), level_);
      if (ZSTD_isError(written) != 0) {
        throw std::runtime_error(std::string("zstd compression failed: ") +
                                 ZSTD_getErrorName(written));
      }
      out.grow(written);
      return;
    }
    case Compression::lz4: {
      const LZ4F_preferences_t preferences = lz4_preferences(input.size(), level_);
      const std::size_t bound = LZ4F_compressFrameBound(input.size(), &preferences);
      std::uint8_t* dst = out.tail(bound);
      std::size_t written = LZ4F_compressBegin(lz4_cctx(context_), dst, bound, &preferences);
      check_lz4(written, "lz4 compression");
      std::size_t more = LZ4F_compressUpdate(lz4_cctx(context_), dst + written, bound - written,
                                             input.data(), input.size(), nullptr);
      check_lz4(more, "lz4 compression");
      written += more;
      more = LZ4F_compressEnd(lz4_cctx(context_), dst + written, bound - written, nullptr);
      check_lz4(more, "lz4 compression");
      out.grow(written + more);
      return;
    }
  }
}

Decompressor::~Decompressor() {
  ZSTD_freeDCtx(static_cast<ZSTD_DCtx*>(zstd_));
  if (lz4_ != nullptr) {
    LZ4F_freeDecompressionContext(static_cast<LZ4F_dctx*>(lz4_));
  }
}

std::optional<std::uint64_t> declared_size(std::string_view compression,
                                           std::span<const std::uint8_t> input) {
  if (compression == "zstd") {
    const unsigned long long size = ZSTD_getFrameContentSize(input.data(), input.size());
    if (size == ZSTD_CONTENTSIZE_ERROR) {
      throw std::runtime_error("zstd: not a zstd frame");
    }
    return size == ZSTD_CONTENTSIZE_UNKNOWN ? std::nullopt : std::optional<std::uint64_t>(size);
  }
  if (compression == "lz4") {
    // Frame header: magic 0x184D2204, FLG (bit 3: content size present), BD,
    // then the 8-byte little-endian content size when present.
    constexpr std::uint32_t kLz4Magic = 0x184D2204u;
    if (input.size() < 6 || load_le<std::uint32_t>(input.data()) != kLz4Magic) {
      throw std::runtime_error("lz4: not an LZ4 frame");
    }
    if ((input[4] & 0x08u) == 0 || input.size() < 6 + 8) {
      return std::nullopt;
    }
    return load_le<std::uint64_t>(input.data() + 6);
  }
  return std::nullopt;
}

void Decompressor::decompress(std::string_view compression, std::span<const std::uint8_t> input,
                              std::span<std::uint8_t> out) {
  if (compression == "zstd") {
    if (zstd_ == nullptr) {
      zstd_ = ZSTD_createDCtx();
      if (zstd_ == nullptr) {
        throw std::runtime_error("cannot create a zstd decompression context");
      }
    }
    const std::size_t written = ZSTD_decompressDCtx(static_cast<ZSTD_DCtx*>(zstd_), out.data(),
                                                    out.size(), input.data(), input.size());
    if (ZSTD_isError(written) != 0) {
      throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(written));
    }
    if (written != out.size()) {
      throw std::runtime_error("zstd data decompresses to " + std::to_string(written) +
                               " bytes, the chunk says " + std::to_string(out.size()));
    }
    return;
  }
  if (compression == "lz4") {
    if (lz4_ == nullptr) {
      LZ4F_dctx* dctx = nullptr;
      check_lz4(LZ4F_createDecompressionContext(&dctx, LZ4F_VERSION), "lz4 context");
      lz4_ = dctx;
    }
    auto* dctx = static_cast<LZ4F_dctx*>(lz4_);
    LZ4F_resetDecompressionContext(dctx);
    std::size_t in_done = 0;
    std::size_t out_done = 0;
    // LZ4F_decompress returns 0 once the frame is complete, else a size hint.
    for (;;) {
      std::size_t in_size = input.size() - in_done;
      std::size_t out_size = out.size() - out_done;
      const std::size_t hint = LZ4F_decompress(dctx, out.data() + out_done, &out_size,
                                               input.data() + in_done, &in_size, nullptr);
      check_lz4(hint, "lz4");
      in_done += in_size;
      out_done += out_size;
      if (hint == 0) {
        break;
      }
      if (in_size == 0 && out_size == 0) {
        throw std::runtime_error(in_done == input.size()
                                     ? "lz4: the frame ends early"
                                     : "lz4 data decompresses to more than the " +
                                           std::to_string(out.size()) + " bytes the chunk says");
      }
    }
    if (out_done != out.size()) {
      throw std::runtime_error("lz4 data decompresses to " + std::to_string(out_done) +
                               " bytes, the chunk says " + std::to_string(out.size()));
    }
    return;
  }
  throw std::runtime_error("unsupported compression '" + std::string(compression) + "'");
}

}  // namespace wbi::mcap::detail
