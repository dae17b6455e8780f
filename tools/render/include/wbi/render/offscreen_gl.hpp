// An OpenGL context without a display: EGL on Mesa's surfaceless platform
// (EGL_PLATFORM_SURFACELESS_MESA, llvmpipe software rasteriser when there is
// no GPU), current on the constructing thread. MuJoCo's renderer then draws
// into its own offscreen framebuffer (mjFB_OFFSCREEN).
#pragma once

#include <stdexcept>

namespace wbi::render {

// Rendering cannot start here; the message is one line naming the Debian
// package that is missing or the EGL call that failed.
class RenderUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class OffscreenGl {
 public:
  // Throws RenderUnavailable.
  OffscreenGl();
  ~OffscreenGl();
  OffscreenGl(const OffscreenGl&) = delete;
  OffscreenGl& operator=(const OffscreenGl&) = delete;

  // "llvmpipe (LLVM 15.0.6, 256 bits)": what renders (GL_RENDERER).
  const char* renderer() const;

 private:
  void* display_ = nullptr;
  void* context_ = nullptr;
};

}  // namespace wbi::render
