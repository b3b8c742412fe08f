// Mesa's OSMesa as the real OpenGL the conformance cases are compared with: a legacy
// GL 2.1 context with RGBA8 colour, 24-bit depth, 8-bit stencil and a 16-bit accumulation buffer.
// The gallium driver (softpipe or llvmpipe) is chosen by GALLIUM_DRIVER before the first context.
#pragma once

#include <string>

#include "osmesa/scenario.h"

namespace shadowref::conformance {

// Renders a scenario with Mesa: identity model-view and projection, so the clip-space vertices go
// to glVertex4d unchanged, and every RenderState field is translated to its GL call.
// Throws std::runtime_error if no context can be created.
Readback renderWithMesa(const Scenario& scenario);

// GL_RENDERER of the context, e.g. "softpipe" or "llvmpipe (LLVM 15.0.6, 256 bits)".
std::string mesaRenderer();
// The short driver name for reports: "softpipe", "llvmpipe" or the renderer string.
std::string mesaDriverName();

}  // namespace shadowref::conformance
