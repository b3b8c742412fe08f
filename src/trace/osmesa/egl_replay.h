// Replay on a real OpenGL through EGL where the machine has it: Mesa's surfaceless platform
// (EGL_MESA_platform_surfaceless: no window system, no display server), a desktop OpenGL context
// (eglBindAPI(EGL_OPENGL_API)) of version 2.1 or later in the compatibility profile, made current
// without a surface (EGL_KHR_surfaceless_context), drawing into a framebuffer object with an RGBA8
// and a DEPTH24_STENCIL8 renderbuffer. Everything else is the OSMesa replay's (osmesa_replay.h):
// the same GL calls, state and read-back. A framebuffer object has no accumulation buffer, so a
// trace that uses one is refused (replay it on osmesa:).
#pragma once

#include <string>

#include "trace/trace.h"
#include "trace/trace_replay.h"

namespace shadowref::trace {

// driver: "llvmpipe" or "softpipe". Throws std::runtime_error saying which EGL step failed.
ReplayResult replayOnEgl(const Trace& trace, const std::string& driver);

}  // namespace shadowref::trace
