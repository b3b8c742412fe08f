#include "raster/clear.h"

#include <algorithm>

#include "raster/fragment_ops.h"

namespace shadowref {

Rect clearRegion(const Framebuffer& fb, const RenderState& state) {
  int x0 = 0, y0 = 0, x1 = fb.width(), y1 = fb.height();
  if (state.scissorTest) {
    x0 = std::max(x0, state.scissor.x);
    y0 = std::max(y0, state.scissor.y);
    x1 = std::min(x1, state.scissor.x + state.scissor.width);
    y1 = std::min(y1, state.scissor.y + state.scissor.height);
  }
  return Rect{x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

namespace {

template <class Fn>
void forEachClearedPixel(const Framebuffer& fb, const RenderState& state, Fn&& fn) {
  const Rect r = clearRegion(fb, state);
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) fn(fb.index(x, y));
}

}  // namespace

void clearColor(Framebuffer& fb, const RenderState& state, const glm::vec4& value) {
  fb.ensureColor();
  const glm::dvec4 v(glm::clamp(value, 0.0f, 1.0f));
  forEachClearedPixel(fb, state, [&](size_t i) { fb.color()[i] = writeColor(fb.color()[i], v, state.colorMask); });
}

void clearDepth(Framebuffer& fb, const RenderState& state, double value) {
  fb.ensureDepth();
  if (!state.depthWrite) return;
  const uint32_t code = fb.depthCodec().encode(value);
  forEachClearedPixel(fb, state, [&](size_t i) { fb.depthCodes()[i] = code; });
}

void clearStencil(Framebuffer& fb, const RenderState& state, int value) {
  fb.ensureStencil();
  const uint8_t v = uint8_t(value & 0xFF);  // GL masks the clear value to the buffer's bits
  const uint8_t mask = state.stencil[FrontFacing].writeMask;
  forEachClearedPixel(fb, state, [&](size_t i) { fb.stencil()[i] = writeStencil(fb.stencil()[i], v, mask); });
}

void clearAccum(Framebuffer& fb, const RenderState& state, const glm::vec4& value) {
  fb.ensureAccum();
  const glm::vec4 v = glm::clamp(value, -1.0f, 1.0f);
  forEachClearedPixel(fb, state, [&](size_t i) { fb.accum()[i] = v; });
}

}  // namespace shadowref
