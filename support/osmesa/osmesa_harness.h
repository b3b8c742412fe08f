// Mesa's OSMesa for the benchmarks (bench/vs_mesa) and the conformance tests: the product's OSMesa
// context (src/trace/osmesa/osmesa_replay.h: OSMESA_RGBA, 24-bit depth, 8-bit stencil, a 16-bit
// accumulation buffer, checked), one per size, kept for the process and made current on request.
// The conformance cases themselves run as traces through `shadowref replay`'s code
// (tests/conformance/comparison.h). The gallium driver (softpipe or llvmpipe) is chosen by
// GALLIUM_DRIVER before the first context.
#pragma once

#include <string>

#include "trace/osmesa/osmesa_replay.h"

namespace shadowref::conformance {

// The context of that size, current, with the fixed-function defaults of a replay
// (trace::setFixedFunctionDefaults). Throws std::runtime_error if no context can be created.
trace::OsmesaContext& mesaContext(int width, int height);

// GL_RENDERER of the context, e.g. "softpipe" or "llvmpipe (LLVM 15.0.6, 256 bits)".
std::string mesaRenderer();
// The short driver name for reports: "softpipe", "llvmpipe" or the renderer string.
std::string mesaDriverName();

}  // namespace shadowref::conformance
