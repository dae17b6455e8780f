// EGL on Mesa's surfaceless platform (offscreen_gl.hpp).
#include "wbi/render/offscreen_gl.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <cstdio>
#include <cstring>
#include <string>

namespace wbi::render {

namespace {

constexpr const char* kInstall =
    "install libegl-mesa0 and libgl1-mesa-dri (Debian; scripts/install-deps)";

std::string egl_error() {
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%04x", static_cast<unsigned>(eglGetError()));
  return hex;
}

}  // namespace

OffscreenGl::OffscreenGl() {
  const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (extensions == nullptr ||
      std::strstr(extensions, "EGL_MESA_platform_surfaceless") == nullptr) {
    throw RenderUnavailable(
        std::string("no EGL surfaceless platform (EGL_MESA_platform_surfaceless): ") + kInstall);
  }
  const auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_display == nullptr) {
    throw RenderUnavailable(std::string("EGL has no eglGetPlatformDisplayEXT: ") + kInstall);
  }
  EGLDisplay display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0;
  EGLint minor = 0;
  if (display == EGL_NO_DISPLAY || eglInitialize(display, &major, &minor) != EGL_TRUE) {
    throw RenderUnavailable("EGL surfaceless display did not start (EGL error " + egl_error() +
                            "): " + kInstall);
  }
  display_ = display;
  // No window: MuJoCo draws into its own framebuffer object (mjFB_OFFSCREEN),
  // so the configuration needs neither a window nor a depth buffer.
  const EGLint config_attributes[] = {
      EGL_SURFACE_TYPE,    EGL_PBUFFER_BIT, EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
      EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,  EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (eglChooseConfig(display, config_attributes, &config, 1, &count) != EGL_TRUE || count < 1 ||
      eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
    eglTerminate(display);
    throw RenderUnavailable("EGL has no desktop OpenGL configuration (EGL error " + egl_error() +
                            "): " + kInstall);
  }
  // The default (compatibility) profile: MuJoCo 2.2 draws with the fixed pipeline.
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (context == EGL_NO_CONTEXT ||
      eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
    if (context != EGL_NO_CONTEXT) {
      eglDestroyContext(display, context);
    }
    eglTerminate(display);
    throw RenderUnavailable("EGL OpenGL context did not start (EGL error " + egl_error() +
                            "): " + kInstall);
  }
  context_ = context;
}

OffscreenGl::~OffscreenGl() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

const char* OffscreenGl::renderer() const {
  // Through EGL, so that this library does not link libGL (MuJoCo loads its own).
  constexpr unsigned kGlRenderer = 0x1F01;
  using GetString = const unsigned char* (*)(unsigned);
  const auto get_string = reinterpret_cast<GetString>(eglGetProcAddress("glGetString"));
  const unsigned char* name = get_string != nullptr ? get_string(kGlRenderer) : nullptr;
  return name != nullptr ? reinterpret_cast<const char*>(name) : "unknown";
}

}  // namespace wbi::render
