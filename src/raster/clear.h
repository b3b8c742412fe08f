// glClear for each buffer, with GL's semantics: the scissor box limits it, and the colour mask,
// depth mask and (front) stencil write mask apply (GL 2.1 §4.2.3). Clearing allocates the buffer.
#pragma once

#include <glm/glm.hpp>

#include "raster/framebuffer.h"
#include "raster/render_state.h"

namespace shadowref {

// The pixels a clear or an accumulation operation touches: the buffer, cut to the scissor box.
Rect clearRegion(const Framebuffer& fb, const RenderState& state);

void clearColor(Framebuffer& fb, const RenderState& state, const glm::vec4& value);
void clearDepth(Framebuffer& fb, const RenderState& state, double value);
void clearStencil(Framebuffer& fb, const RenderState& state, int value);
void clearAccum(Framebuffer& fb, const RenderState& state, const glm::vec4& value);

}  // namespace shadowref
