// glClear for each buffer, with GL's semantics: the scissor box limits it, and the colour mask,
// depth mask and (front) stencil write mask apply (GL 2.1 §4.2.3). Clearing allocates the buffer.
#pragma once

#include <glm/glm.hpp>

#include "raster/framebuffer.h"
#include "raster/render_state.h"
#include "raster/thread_pool.h"

namespace shadowref {

// The pixels a clear or an accumulation operation touches: the buffer, cut to the scissor box.
Rect clearRegion(const Framebuffer& fb, const RenderState& state);

void clearColor(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel = {});
void clearDepth(Framebuffer& fb, const RenderState& state, double value, const ParallelFor& parallel = {});
void clearStencil(Framebuffer& fb, const RenderState& state, int value, const ParallelFor& parallel = {});
void clearAccum(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel = {});

}  // namespace shadowref
