// Per-fragment operations in OpenGL order ([GL 2.1, §4.1]): scissor -> stencil test -> depth test
// -> stencil update -> blend -> masked writes. One small function per operation, so the answer to
// "what does DECR_WRAP do" is in one place.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include <glm/glm.hpp>

#include "gl/render_state.h"

namespace shadowref {

// The per-fragment operations are defined inline here: they run once per fragment, and a call
// across translation units for each would cost more than the operation itself.
inline bool scissorTest(const RenderState& state, int x, int y) {
  if (!state.scissorTest) return true;
  const Rect& r = state.scissor;
  return x >= r.x && x < r.x + r.width && y >= r.y && y < r.y + r.height;
}

inline bool compare(CompareFunc func, uint32_t incoming, uint32_t stored) {
  switch (func) {
    case CompareFunc::Never: return false;
    case CompareFunc::Less: return incoming < stored;
    case CompareFunc::Equal: return incoming == stored;
    case CompareFunc::LEqual: return incoming <= stored;
    case CompareFunc::Greater: return incoming > stored;
    case CompareFunc::NotEqual: return incoming != stored;
    case CompareFunc::GEqual: return incoming >= stored;
    case CompareFunc::Always: return true;
  }
  return false;
}

// The reference as the stencil test compares it: clamped to [0, 255], as GL does, then masked.
inline uint32_t maskedStencilReference(const StencilFaceState& s) { return uint32_t(std::clamp(s.ref, 0, 255)) & s.mask; }

inline bool stencilTest(const StencilFaceState& s, uint8_t stored) {
  return compare(s.func, maskedStencilReference(s), uint32_t(stored) & s.mask);
}

inline uint8_t applyStencilOp(StencilOp op, uint8_t stored, int ref) {
  switch (op) {
    case StencilOp::Keep: return stored;
    case StencilOp::Zero: return 0;
    case StencilOp::Replace: return uint8_t(std::clamp(ref, 0, 255));
    case StencilOp::Incr: return stored == 255 ? 255 : uint8_t(stored + 1);   // saturates
    case StencilOp::Decr: return stored == 0 ? 0 : uint8_t(stored - 1);       // saturates
    case StencilOp::Invert: return uint8_t(~stored);
    case StencilOp::IncrWrap: return uint8_t(stored + 1);                     // 255 -> 0
    case StencilOp::DecrWrap: return uint8_t(stored - 1);                     // 0 -> 255
  }
  return stored;
}

inline uint8_t writeStencil(uint8_t stored, uint8_t computed, uint8_t writeMask) {
  return uint8_t((stored & ~writeMask) | (computed & writeMask));
}

// Whether an op, through this write mask, can change some stored stencil byte: KEEP never does, a
// zero mask keeps every bit, and every other op changes some byte through any other mask. The
// fast paths ask this to know where the stencil buffer is only read.
inline bool stencilOpMayWrite(StencilOp op, uint8_t writeMask) { return writeMask != 0 && op != StencilOp::Keep; }

// The same for any of a face's three ops: whether drawing with it can change the stencil buffer.
inline bool stencilFaceMayWrite(const StencilFaceState& s) {
  return stencilOpMayWrite(s.sfail, s.writeMask) || stencilOpMayWrite(s.dpfail, s.writeMask) ||
         stencilOpMayWrite(s.dppass, s.writeMask);
}

inline bool depthTest(CompareFunc func, uint32_t fragmentCode, uint32_t storedCode) {
  return compare(func, fragmentCode, storedCode);
}

inline double blendFactor(BlendFactor f, int c, const glm::dvec4& src, const glm::dvec4& dst) {
  switch (f) {
    case BlendFactor::Zero: return 0.0;
    case BlendFactor::One: return 1.0;
    case BlendFactor::SrcColor: return src[c];
    case BlendFactor::OneMinusSrcColor: return 1.0 - src[c];
    case BlendFactor::DstColor: return dst[c];
    case BlendFactor::OneMinusDstColor: return 1.0 - dst[c];
    case BlendFactor::SrcAlpha: return src.a;
    case BlendFactor::OneMinusSrcAlpha: return 1.0 - src.a;
    case BlendFactor::DstAlpha: return dst.a;
    case BlendFactor::OneMinusDstAlpha: return 1.0 - dst.a;
  }
  return 0.0;
}

inline glm::dvec4 blend(const BlendState& b, const glm::dvec4& src, const glm::dvec4& dst) {
  if (!b.enabled) return src;
  // GL clamps the source colour to [0, 1] for fixed-point buffers before blending.
  const glm::dvec4 s = glm::clamp(src, 0.0, 1.0);
  glm::dvec4 out;
  for (int c = 0; c < 4; ++c)
    out[c] = s[c] * blendFactor(b.src, c, s, dst) + dst[c] * blendFactor(b.dst, c, s, dst);
  return out;
}

inline glm::vec4 writeColor(const glm::vec4& stored, const glm::dvec4& computed, const std::array<bool, 4>& mask) {
  glm::vec4 out = stored;
  for (int c = 0; c < 4; ++c)
    if (mask[c]) out[c] = float(std::clamp(computed[c], 0.0, 1.0));
  return out;
}

}  // namespace shadowref
