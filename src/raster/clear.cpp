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

// Runs fn(first, count) for each row of the cleared region: the pixels [first, first + count).
template <class Fn>
void forEachClearedRow(const Framebuffer& fb, const RenderState& state, Fn&& fn) {
  const Rect r = clearRegion(fb, state);
  if (r.width == 0) return;
  if (r.x == 0 && r.width == fb.width()) {  // whole rows: one run
    fn(fb.index(0, r.y), size_t(r.width) * size_t(r.height));
    return;
  }
  for (int y = r.y; y < r.y + r.height; ++y) fn(fb.index(r.x, y), size_t(r.width));
}

bool coversWholeBuffer(const Framebuffer& fb, const RenderState& state) {
  const Rect r = clearRegion(fb, state);
  return r.x == 0 && r.y == 0 && r.width == fb.width() && r.height == fb.height();
}

}  // namespace

// A buffer that does not exist yet and is cleared whole is allocated with the cleared value in one
// pass (frames allocate their buffers anew: half the memory traffic of allocate-then-fill).
void clearColor(Framebuffer& fb, const RenderState& state, const glm::vec4& value) {
  const glm::dvec4 v(glm::clamp(value, 0.0f, 1.0f));
  const auto& mask = state.colorMask;
  const bool allChannels = mask[0] && mask[1] && mask[2] && mask[3];
  if (allChannels && !fb.hasColor() && coversWholeBuffer(fb, state)) {
    fb.color().assign(size_t(fb.width()) * size_t(fb.height()), writeColor(glm::vec4(0.0f), v, mask));
    return;
  }
  fb.ensureColor();
  glm::vec4* color = fb.color().data();
  if (allChannels) {
    const glm::vec4 written = writeColor(glm::vec4(0.0f), v, mask);  // no stored channel survives
    forEachClearedRow(fb, state, [&](size_t first, size_t count) { std::fill_n(color + first, count, written); });
    return;
  }
  forEachClearedRow(fb, state, [&](size_t first, size_t count) {
    for (size_t i = first; i < first + count; ++i) color[i] = writeColor(color[i], v, mask);
  });
}

void clearDepth(Framebuffer& fb, const RenderState& state, double value) {
  const uint32_t code = fb.depthCodec().encode(value);
  if (state.depthWrite && !fb.hasDepth() && coversWholeBuffer(fb, state)) {
    fb.depthCodes().assign(size_t(fb.width()) * size_t(fb.height()), code);
    return;
  }
  fb.ensureDepth();
  if (!state.depthWrite) return;
  uint32_t* depth = fb.depthCodes().data();
  forEachClearedRow(fb, state, [&](size_t first, size_t count) { std::fill_n(depth + first, count, code); });
}

void clearStencil(Framebuffer& fb, const RenderState& state, int value) {
  const uint8_t v = uint8_t(value & 0xFF);  // GL masks the clear value to the buffer's bits
  const uint8_t mask = state.stencil[FrontFacing].writeMask;
  if (mask == 0xFF && !fb.hasStencil() && coversWholeBuffer(fb, state)) {
    fb.stencil().assign(size_t(fb.width()) * size_t(fb.height()), v);
    return;
  }
  fb.ensureStencil();
  uint8_t* stencil = fb.stencil().data();
  forEachClearedRow(fb, state, [&](size_t first, size_t count) {
    if (mask == 0xFF) std::fill_n(stencil + first, count, v);
    else
      for (size_t i = first; i < first + count; ++i) stencil[i] = writeStencil(stencil[i], v, mask);
  });
}

void clearAccum(Framebuffer& fb, const RenderState& state, const glm::vec4& value) {
  fb.ensureAccum();
  const glm::vec4 v = glm::clamp(value, -1.0f, 1.0f);
  glm::vec4* accum = fb.accum().data();
  forEachClearedRow(fb, state, [&](size_t first, size_t count) { std::fill_n(accum + first, count, v); });
}

}  // namespace shadowref
