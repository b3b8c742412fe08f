// RenderState as OpenGL state, for the places that drive Mesa with shadowref's states: `replay
// --on osmesa:*|egl:*` (osmesa_replay.cpp, which the conformance cases run through) and
// bench/vs-mesa's frames (bench/mesa_frame.cpp).
#pragma once

#include <GL/osmesa.h>

#include <stdexcept>
#include <string>

#include "gl/accumulation.h"
#include "gl/render_state.h"

namespace shadowref::conformance {

// A GL entry point past GL 1.1 through OSMesaGetProcAddress (gl.h declares only GL 1.1 without
// GL_GLEXT_PROTOTYPES); std::runtime_error if Mesa lacks it. Needs a current context. The entry
// points dispatch to the current Mesa context, also one made current through EGL (both use
// libglapi).
template <class Fn>
Fn loadGlFunction(const char* name) {
  auto fn = reinterpret_cast<Fn>(OSMesaGetProcAddress(name));
  if (!fn) throw std::runtime_error(std::string("OSMesa lacks ") + name);
  return fn;
}

// The separate-stencil calls (GL 2.0) applyRenderState needs.
struct GlStencilFunctions {
  PFNGLSTENCILFUNCSEPARATEPROC funcSeparate = nullptr;
  PFNGLSTENCILOPSEPARATEPROC opSeparate = nullptr;
  PFNGLSTENCILMASKSEPARATEPROC maskSeparate = nullptr;
  static GlStencilFunctions load();
};

GLenum glCompare(CompareFunc f);
GLenum glStencilOpOf(StencilOp op);
GLenum glBlendFactorOf(BlendFactor f);
GLenum glAccumOpOf(AccumOp op);

// Every field of RenderState as GL state. RenderState::clipFar has no GL counterpart (GL clips at
// the far plane unless depth clamp is on): the conformance cases with clipFar off put nothing
// beyond the far plane, and under P_inf the points at infinity have z = w exactly, which passes
// GL's z <= w.
void applyRenderState(const RenderState& s, const GlStencilFunctions& stencil);

}  // namespace shadowref::conformance
