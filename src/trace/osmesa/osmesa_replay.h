// Replay of a trace on a real OpenGL: Mesa through OSMesa, or through EGL's surfaceless platform
// (egl_replay.h), with the gallium driver (softpipe, llvmpipe) chosen by GALLIUM_DRIVER before
// the process's first context. Each framebuffer of the trace is drawn in a context of its own
// with 24-bit depth and 8-bit stencil, in the trace's FixedFunction mode (trace_replay.h):
// identity matrices, clip coordinates given to glVertex4d, each vertex's colour the shader's at
// that vertex (glColor4d, GL_SMOOTH), every RenderState field as its GL call (gl_state.h),
// dithering off. Read back as glReadPixels gives it: colour bytes / 255, depth codes >> 8,
// stencil bytes.
#pragma once

#include <GL/osmesa.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "trace/osmesa/gl_state.h"
#include "trace/trace.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

// A current GL context drawing into a framebuffer of its own size, RGBA8 colour, 24-bit depth,
// 8-bit stencil (and, where it has one, a 16-bit accumulation buffer).
class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual bool hasAccumulation() const = 0;
  const conformance::GlStencilFunctions& stencil() const { return stencil_; }
  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer() const { return renderer_; }

 protected:
  // Once the context is current: the separate-stencil entry points and the renderer string.
  void loadCommon();

 private:
  conformance::GlStencilFunctions stencil_;
  std::string renderer_;
};

// OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 16): checked for 24-bit depth, 8-bit stencil and a
// 16-bit accumulation buffer, current on construction and after makeCurrent(). Throws
// std::runtime_error when Mesa cannot make it.
class OsmesaContext : public GlContext {
 public:
  OsmesaContext(int width, int height);
  ~OsmesaContext() override;
  OsmesaContext(const OsmesaContext&) = delete;
  OsmesaContext& operator=(const OsmesaContext&) = delete;
  bool hasAccumulation() const override { return true; }
  void makeCurrent();
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  int width_, height_;
  std::vector<unsigned char> pixels_;
  OSMesaContext context_ = nullptr;
};

// The GL state every replayed framebuffer starts from: identity matrices, smooth shading, no
// lighting, no dithering (it would perturb the 8-bit colour by up to one unit).
void setFixedFunctionDefaults();

// Runs the trace with a context per framebuffer from `make`, after asking Mesa for `driver`
// (GALLIUM_DRIVER) and checking the renderer says so. Throws std::runtime_error, also when a
// framebuffer needs an accumulation buffer its context lacks.
ReplayResult replayOnGl(const Trace& trace, const std::string& driver,
                        const std::function<std::unique_ptr<GlContext>(int width, int height)>& make);

// driver: "llvmpipe" or "softpipe". Throws std::runtime_error when no context can be made or
// Mesa renders with another driver than asked for (GALLIUM_DRIVER was fixed by an earlier
// context of the process).
ReplayResult replayOnOsmesa(const Trace& trace, const std::string& driver);

// GL_RENDERER of the last context a replay made, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
std::string osmesaRenderer();

}  // namespace shadowref::trace
