// Per-fragment operations in OpenGL order (GL 2.1 §4.1): scissor -> stencil test -> depth test ->
// stencil update -> blend -> masked writes. One small function per operation, so the answer to
// "what does DECR_WRAP do" is in one place.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "raster/render_state.h"

namespace shadowref {

bool scissorTest(const RenderState& state, int x, int y);

bool compare(CompareFunc func, uint32_t incoming, uint32_t stored);

// Stencil test: (ref & mask) func (stored & mask); ref clamped to [0, 255].
bool stencilTest(const StencilFaceState& s, uint8_t stored);

// The new stencil value for one op; the write mask is applied by writeStencil.
uint8_t applyStencilOp(StencilOp op, uint8_t stored, int ref);

// Only the bits set in the write mask change.
uint8_t writeStencil(uint8_t stored, uint8_t computed, uint8_t writeMask);

// Depth test on the buffer's codes (the fragment depth already converted to the buffer format).
bool depthTest(CompareFunc func, uint32_t fragmentCode, uint32_t storedCode);

double blendFactor(BlendFactor f, int channel, const glm::dvec4& src, const glm::dvec4& dst);
glm::dvec4 blend(const BlendState& b, const glm::dvec4& src, const glm::dvec4& dst);

// Colour as a fixed-point GL colour buffer stores it: clamped to [0, 1], masked per channel.
glm::vec4 writeColor(const glm::vec4& stored, const glm::dvec4& computed, const std::array<bool, 4>& mask);

}  // namespace shadowref
