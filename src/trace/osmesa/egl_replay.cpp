#include "trace/osmesa/egl_replay.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "trace/osmesa/osmesa_replay.h"

namespace shadowref::trace {

namespace {

std::string eglFailure(const char* step) {
  char text[96];
  std::snprintf(text, sizeof text, "EGL: %s failed (error 0x%04X)", step, unsigned(eglGetError()));
  return text;
}

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

template <class Fn>
Fn eglFunction(const char* name) {
  auto fn = reinterpret_cast<Fn>(eglGetProcAddress(name));
  if (!fn) throw std::runtime_error(std::string("EGL: no ") + name);
  return fn;
}

// The surfaceless display, initialised once for the process (EGL displays are per process;
// the operating system releases it at exit).
EGLDisplay surfacelessDisplay() {
  static EGLDisplay display = [] {
    if (!hasExtension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_MESA_platform_surfaceless"))
      throw std::runtime_error("EGL: the client lacks EGL_MESA_platform_surfaceless (Mesa's libegl-mesa0)");
    const auto getPlatformDisplay = eglFunction<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d == EGL_NO_DISPLAY) throw std::runtime_error(eglFailure("eglGetPlatformDisplayEXT(surfaceless)"));
    EGLint major = 0, minor = 0;
    if (!eglInitialize(d, &major, &minor)) throw std::runtime_error(eglFailure("eglInitialize"));
    const char* extensions = eglQueryString(d, EGL_EXTENSIONS);
    for (const char* needed : {"EGL_KHR_no_config_context", "EGL_KHR_surfaceless_context", "EGL_KHR_create_context"})
      if (!hasExtension(extensions, needed)) throw std::runtime_error(std::string("EGL: the display lacks ") + needed);
    return d;
  }();
  return display;
}

class EglContext : public GlContext {
 public:
  EglContext(int width, int height) : display_(surfacelessDisplay()) {
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error(eglFailure("eglBindAPI(EGL_OPENGL_API)"));
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 2, EGL_CONTEXT_MINOR_VERSION, 1, EGL_NONE};
    context_ = eglCreateContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context_ == EGL_NO_CONTEXT) throw std::runtime_error(eglFailure("eglCreateContext(OpenGL 2.1)"));
    try {
      if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
        throw std::runtime_error(eglFailure("eglMakeCurrent(no surface)"));
      genFramebuffers_ = eglFunction<PFNGLGENFRAMEBUFFERSPROC>("glGenFramebuffers");
      bindFramebuffer_ = eglFunction<PFNGLBINDFRAMEBUFFERPROC>("glBindFramebuffer");
      deleteFramebuffers_ = eglFunction<PFNGLDELETEFRAMEBUFFERSPROC>("glDeleteFramebuffers");
      genRenderbuffers_ = eglFunction<PFNGLGENRENDERBUFFERSPROC>("glGenRenderbuffers");
      bindRenderbuffer_ = eglFunction<PFNGLBINDRENDERBUFFERPROC>("glBindRenderbuffer");
      deleteRenderbuffers_ = eglFunction<PFNGLDELETERENDERBUFFERSPROC>("glDeleteRenderbuffers");
      const auto storage = eglFunction<PFNGLRENDERBUFFERSTORAGEPROC>("glRenderbufferStorage");
      const auto attach = eglFunction<PFNGLFRAMEBUFFERRENDERBUFFERPROC>("glFramebufferRenderbuffer");
      const auto status = eglFunction<PFNGLCHECKFRAMEBUFFERSTATUSPROC>("glCheckFramebufferStatus");
      genFramebuffers_(1, &framebuffer_);
      bindFramebuffer_(GL_FRAMEBUFFER, framebuffer_);
      genRenderbuffers_(2, renderbuffers_);
      bindRenderbuffer_(GL_RENDERBUFFER, renderbuffers_[0]);
      storage(GL_RENDERBUFFER, GL_RGBA8, width, height);
      attach(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffers_[0]);
      bindRenderbuffer_(GL_RENDERBUFFER, renderbuffers_[1]);
      storage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width, height);
      attach(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, renderbuffers_[1]);
      attach(GL_FRAMEBUFFER, GL_STENCIL_ATTACHMENT, GL_RENDERBUFFER, renderbuffers_[1]);
      // The framebuffer object is drawn upside down in gallium's y-down surface, as a window's
      // buffer is (GL_MESA_framebuffer_flip_y). OSMesa's buffer is a window's, so llvmpipe then sets
      // up every triangle from the same window coordinates on both targets and their buffers are
      // byte for byte the same; unflipped, the viewport transform and the plane evaluation start
      // from the other corner and rounding differs (docs/trace-format.md). The core entry point:
      // Mesa's compatibility profile refuses glFramebufferParameteriMESA (INVALID_OPERATION).
      if (!hasExtension(reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS)), "GL_MESA_framebuffer_flip_y"))
        throw std::runtime_error("EGL: the context lacks GL_MESA_framebuffer_flip_y");
      eglFunction<PFNGLFRAMEBUFFERPARAMETERIPROC>("glFramebufferParameteri")(GL_FRAMEBUFFER, GL_FRAMEBUFFER_FLIP_Y_MESA,
                                                                             GL_TRUE);
      if (glGetError() != GL_NO_ERROR) throw std::runtime_error("EGL: the framebuffer object cannot be y-flipped");
      if (status(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("EGL: the RGBA8 + DEPTH24_STENCIL8 framebuffer object is incomplete");
      glDrawBuffer(GL_COLOR_ATTACHMENT0);
      glReadBuffer(GL_COLOR_ATTACHMENT0);
      GLint depthBits = 0, stencilBits = 0;
      glGetIntegerv(GL_DEPTH_BITS, &depthBits);
      glGetIntegerv(GL_STENCIL_BITS, &stencilBits);
      if (depthBits != 24 || stencilBits != 8)
        throw std::runtime_error("EGL: the framebuffer object lacks 24-bit depth or 8-bit stencil");
      loadCommon();
    } catch (...) {
      release();
      throw;
    }
  }
  ~EglContext() override { release(); }
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;
  bool hasAccumulation() const override { return false; }

 private:
  void release() {
    if (framebuffer_) {
      bindFramebuffer_(GL_FRAMEBUFFER, 0);
      deleteFramebuffers_(1, &framebuffer_);
      deleteRenderbuffers_(2, renderbuffers_);
    }
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }

  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
  GLuint framebuffer_ = 0, renderbuffers_[2] = {0, 0};
  PFNGLGENFRAMEBUFFERSPROC genFramebuffers_ = nullptr;
  PFNGLBINDFRAMEBUFFERPROC bindFramebuffer_ = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC deleteFramebuffers_ = nullptr;
  PFNGLGENRENDERBUFFERSPROC genRenderbuffers_ = nullptr;
  PFNGLBINDRENDERBUFFERPROC bindRenderbuffer_ = nullptr;
  PFNGLDELETERENDERBUFFERSPROC deleteRenderbuffers_ = nullptr;
};

}  // namespace

ReplayResult replayOnEgl(const Trace& trace, const std::string& driver) {
  return replayOnGl(trace, driver, [](int width, int height) { return std::make_unique<EglContext>(width, height); });
}

}  // namespace shadowref::trace
