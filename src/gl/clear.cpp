#include "gl/clear.h"

#include <algorithm>

#include "gl/fragment_ops.h"

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

// The fewest pixels a part of a parallel clear fills: handing out a part costs more than filling
// fewer (a 160x128 test frame is one part; an 800x640 frame 15, a 2048² map 128).
constexpr size_t kPixelsPerPart = 1 << 15;

// Runs fn(first, count) over the region's pixels in rows [y0, y1) in runs [first, first + count)
// — whole rows as one run.
template <class Fn>
void forEachRun(const Framebuffer& fb, const Rect& r, int y0, int y1, Fn&& fn) {
  y0 = std::max(y0, r.y);
  y1 = std::min(y1, r.y + r.height);
  if (r.width == 0 || y0 >= y1) return;
  if (r.x == 0 && r.width == fb.width()) {
    fn(fb.index(0, y0), size_t(r.width) * size_t(y1 - y0));
    return;
  }
  for (int y = y0; y < y1; ++y) fn(fb.index(r.x, y), size_t(r.width));
}

bool coversWholeBuffer(const Framebuffer& fb, const RenderState& state) {
  const Rect r = clearRegion(fb, state);
  return r.x == 0 && r.y == 0 && r.width == fb.width() && r.height == fb.height();
}

bool allChannels(const RenderState& state) {
  return state.colorMask[0] && state.colorMask[1] && state.colorMask[2] && state.colorMask[3];
}

void colorRows(Framebuffer& fb, const RenderState& state, const glm::vec4& value, int y0, int y1) {
  const glm::dvec4 v(glm::clamp(value, 0.0f, 1.0f));
  const auto& mask = state.colorMask;
  glm::vec4* color = fb.color().data();
  const Rect r = clearRegion(fb, state);
  if (allChannels(state)) {
    const glm::vec4 written = writeColor(glm::vec4(0.0f), v, mask);  // no stored channel survives
    forEachRun(fb, r, y0, y1, [&](size_t first, size_t count) { std::fill_n(color + first, count, written); });
    return;
  }
  forEachRun(fb, r, y0, y1, [&](size_t first, size_t count) {
    for (size_t i = first; i < first + count; ++i) color[i] = writeColor(color[i], v, mask);
  });
}

void depthRows(Framebuffer& fb, const RenderState& state, double value, int y0, int y1) {
  if (!state.depthWrite) return;
  const uint32_t code = fb.depthCodec().encode(value);
  uint32_t* depth = fb.depthCodes().data();
  forEachRun(fb, clearRegion(fb, state), y0, y1,
             [&](size_t first, size_t count) { std::fill_n(depth + first, count, code); });
}

void stencilRows(Framebuffer& fb, const RenderState& state, int value, int y0, int y1) {
  const uint8_t v = uint8_t(value & 0xFF);  // GL masks the clear value to the buffer's bits
  const uint8_t mask = state.stencil[FrontFacing].writeMask;
  uint8_t* stencil = fb.stencil().data();
  forEachRun(fb, clearRegion(fb, state), y0, y1, [&](size_t first, size_t count) {
    if (mask == 0xFF) std::fill_n(stencil + first, count, v);
    else
      for (size_t i = first; i < first + count; ++i) stencil[i] = writeStencil(stencil[i], v, mask);
  });
}

void accumRows(Framebuffer& fb, const RenderState& state, const glm::vec4& value, int y0, int y1) {
  const glm::vec4 v = glm::clamp(value, -1.0f, 1.0f);
  glm::vec4* accum = fb.accum().data();
  forEachRun(fb, clearRegion(fb, state), y0, y1,
             [&](size_t first, size_t count) { std::fill_n(accum + first, count, v); });
}

}  // namespace

void prepareClear(Framebuffer& fb, const ClearRequest& c) {
  const bool whole = coversWholeBuffer(fb, c.state);
  if (c.color) {
    if (!fb.hasColor() && allChannels(c.state) && whole) fb.color().resize(fb.pixelCount());
    fb.ensureColor();
  }
  if (c.depth) {
    if (!fb.hasDepth() && c.state.depthWrite && whole) fb.depthCodes().resize(fb.pixelCount());
    fb.ensureDepth();
  }
  if (c.stencil) {
    if (!fb.hasStencil() && c.state.stencil[FrontFacing].writeMask == 0xFF && whole)
      fb.stencil().resize(fb.pixelCount());
    fb.ensureStencil();
  }
  if (c.accum) {
    if (!fb.hasAccum() && whole) fb.accum().resize(fb.pixelCount());
    fb.ensureAccum();
  }
}

void clearRows(Framebuffer& fb, const ClearRequest& c, int y0, int y1) {
  if (c.color) colorRows(fb, c.state, *c.color, y0, y1);
  if (c.depth) depthRows(fb, c.state, *c.depth, y0, y1);
  if (c.stencil) stencilRows(fb, c.state, *c.stencil, y0, y1);
  if (c.accum) accumRows(fb, c.state, *c.accum, y0, y1);
}

void fillClear(Framebuffer& fb, const ClearRequest& c, const ParallelFor& parallel) {
  const Rect r = clearRegion(fb, c.state);
  if (r.width == 0 || r.height == 0) return;
  const size_t pixels = size_t(r.width) * size_t(r.height);
  const int parts = int(std::clamp<size_t>(pixels / kPixelsPerPart, 1, size_t(r.height)));
  auto part = [&](int p) {
    clearRows(fb, c, r.y + int(int64_t(r.height) * p / parts), r.y + int(int64_t(r.height) * (p + 1) / parts));
  };
  if (parts > 1 && parallel) parallel(parts, part);
  else
    for (int p = 0; p < parts; ++p) part(p);
}

void clear(Framebuffer& fb, const ClearRequest& c, const ParallelFor& parallel) {
  prepareClear(fb, c);
  fillClear(fb, c, parallel);
}

void clearColor(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel) {
  clear(fb, ClearRequest{state, value, {}, {}, {}}, parallel);
}
void clearDepth(Framebuffer& fb, const RenderState& state, double value, const ParallelFor& parallel) {
  clear(fb, ClearRequest{state, {}, value, {}, {}}, parallel);
}
void clearStencil(Framebuffer& fb, const RenderState& state, int value, const ParallelFor& parallel) {
  clear(fb, ClearRequest{state, {}, {}, value, {}}, parallel);
}
void clearAccum(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel) {
  clear(fb, ClearRequest{state, {}, {}, {}, value}, parallel);
}

}  // namespace shadowref
