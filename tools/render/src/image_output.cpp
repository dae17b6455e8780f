// PNG and MP4 output (image_output.hpp).
#include "wbi/render/image_output.hpp"

#include <png.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace wbi::render {

namespace {

// The argument quoted for /bin/sh.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  }
  return out + "'";
}

std::string last_line(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (!line.empty()) {
      last = line;
    }
  }
  return last;
}

}  // namespace

void write_png(const std::filesystem::path& file, int width, int height,
               std::span<const std::uint8_t> rgb) {
  const std::string where = file.string();
  if (rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    throw std::invalid_argument(where + ": image of the wrong size");
  }
  std::FILE* out = std::fopen(where.c_str(), "wb");
  if (out == nullptr) {
    throw std::runtime_error(where + ": cannot write the file");
  }
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> closer(out, std::fclose);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error(where + ": libpng did not start");
  }
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(
        rgb.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 3);
  }
  // libpng reports errors by longjmp: nothing with a destructor lives between
  // here and the end of the writing.
  if (setjmp(png_jmpbuf(png)) != 0) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error(where + ": libpng could not write the image");
  }
  png_init_io(png, out);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_rows(png, info, rows.data());
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
}

std::string find_ffmpeg() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const auto candidate = std::filesystem::path(dir.empty() ? "." : dir) / "ffmpeg";
    if (::access(candidate.c_str(), X_OK) == 0) {
      return candidate.string();
    }
  }
  return "";
}

Mp4Writer::Mp4Writer(const std::filesystem::path& file, int width, int height, double fps)
    : file_(file),
      frame_bytes_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
  const std::string ffmpeg = find_ffmpeg();
  if (ffmpeg.empty()) {
    throw std::runtime_error("MP4 output needs the ffmpeg program: install ffmpeg (Debian)");
  }
  log_ = std::filesystem::path(file).concat(".ffmpeg.log");
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  const std::string command =
      quoted(ffmpeg) + " -nostdin -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " +
      std::to_string(width) + "x" + std::to_string(height) + " -r " + rate +
      " -i - -an -c:v libx264 -preset veryfast -crf 20 -pix_fmt yuv420p -movflags +faststart -f "
      "mp4 " +
      quoted(file.string()) + " 2> " + quoted(log_.string());
  pipe_ = ::popen(command.c_str(), "w");
  if (pipe_ == nullptr) {
    throw std::runtime_error(file.string() + ": cannot start ffmpeg");
  }
}

Mp4Writer::~Mp4Writer() {
  if (pipe_ != nullptr) {
    ::pclose(pipe_);
    std::error_code ignored;
    std::filesystem::remove(log_, ignored);
  }
}

void Mp4Writer::write(std::span<const std::uint8_t> rgb) {
  if (rgb.size() != frame_bytes_) {
    throw std::invalid_argument(file_.string() + ": frame of the wrong size");
  }
  if (pipe_ == nullptr || std::fwrite(rgb.data(), 1, rgb.size(), pipe_) != rgb.size()) {
    close();  // throws ffmpeg's message
    throw std::runtime_error(file_.string() + ": ffmpeg stopped reading frames");
  }
}

void Mp4Writer::close() {
  if (pipe_ == nullptr) {
    return;
  }
  const int status = ::pclose(pipe_);
  pipe_ = nullptr;
  const std::string message = last_line(log_);
  std::error_code ignored;
  std::filesystem::remove(log_, ignored);
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(file_.string() + ": ffmpeg failed" +
                             (message.empty() ? std::string() : ": " + message));
  }
}

}  // namespace wbi::render
