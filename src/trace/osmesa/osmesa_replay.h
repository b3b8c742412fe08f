// Replay of a trace on a real OpenGL: Mesa through OSMesa, with the gallium driver (softpipe,
// llvmpipe) chosen by GALLIUM_DRIVER before the process's first context. Each framebuffer of the
// trace is drawn in a context of its own, OSMESA_RGBA with 24-bit depth, 8-bit stencil and a
// 16-bit accumulation buffer, in the trace's FixedFunction mode (trace_replay.h): identity
// matrices, clip coordinates given to glVertex4d, each vertex's colour the shader's at that
// vertex (glColor4d, GL_SMOOTH), every RenderState field as its GL call (gl_state.h), dithering
// off. Read back as glReadPixels gives it: colour bytes / 255, depth codes >> 8, stencil bytes.
#pragma once

#include <string>

#include "trace/trace.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

// driver: "llvmpipe" or "softpipe". Throws std::runtime_error when no context can be made or
// Mesa renders with another driver than asked for (GALLIUM_DRIVER was fixed by an earlier
// context of the process).
ReplayResult replayOnOsmesa(const Trace& trace, const std::string& driver);

// GL_RENDERER of the last context made, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
std::string osmesaRenderer();

}  // namespace shadowref::trace
