// Writing rendered frames: one PNG (libpng), or an H.264 MP4 through a pipe to
// the ffmpeg program (README.md, "Encoding": why a pipe, not libavcodec).
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>

namespace wbi::render {

// RGB, top row first. Throws std::runtime_error naming the file.
void write_png(const std::filesystem::path& file, int width, int height,
               std::span<const std::uint8_t> rgb);

// The ffmpeg program on PATH, or "" (then MP4 output names the package).
std::string find_ffmpeg();

class Mp4Writer {
 public:
  // Starts `ffmpeg` reading raw RGB frames on its stdin and writing H.264
  // (libx264, yuv420p, CRF 20, +faststart) at `fps` into `file`. Throws
  // std::runtime_error when ffmpeg is missing ("install ffmpeg") or cannot start.
  Mp4Writer(const std::filesystem::path& file, int width, int height, double fps);
  // Closes the pipe and waits for ffmpeg (close() without the error).
  ~Mp4Writer();
  Mp4Writer(const Mp4Writer&) = delete;
  Mp4Writer& operator=(const Mp4Writer&) = delete;

  // One frame, width × height × 3 bytes. Throws when ffmpeg has gone.
  void write(std::span<const std::uint8_t> rgb);
  // Ends the stream and waits for ffmpeg; throws with ffmpeg's last message
  // when it failed.
  void close();

 private:
  std::filesystem::path file_;
  std::size_t frame_bytes_;
  std::FILE* pipe_ = nullptr;
  std::filesystem::path log_;  // ffmpeg's stderr, shown when it fails
};

}  // namespace wbi::render
