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

// The fewest pixels a part of a parallel clear fills: handing out a part costs more than filling
// fewer (a 160x128 test frame is one part; an 800x640 frame 15, a 2048² map 128).
constexpr size_t kPixelsPerPart = 1 << 15;

// Runs fn(first, count) over the cleared region's pixels in runs [first, first + count) — whole
// rows as one run — cut into parts of rows that `parallel` may fill at once. Every pixel is
// written once by one part, so the bytes do not depend on the thread count.
template <class Fn>
void forEachClearedRun(const Framebuffer& fb, const RenderState& state, const ParallelFor& parallel, Fn&& fn) {
  const Rect r = clearRegion(fb, state);
  if (r.width == 0 || r.height == 0) return;
  const size_t pixels = size_t(r.width) * size_t(r.height);
  const int parts = int(std::clamp<size_t>(pixels / kPixelsPerPart, 1, size_t(r.height)));
  const bool wholeRows = r.x == 0 && r.width == fb.width();
  auto part = [&](int p) {
    const int y0 = r.y + int(int64_t(r.height) * p / parts), y1 = r.y + int(int64_t(r.height) * (p + 1) / parts);
    if (wholeRows) fn(fb.index(0, y0), size_t(r.width) * size_t(y1 - y0));
    else
      for (int y = y0; y < y1; ++y) fn(fb.index(r.x, y), size_t(r.width));
  };
  if (parts > 1 && parallel) parallel(parts, part);
  else
    for (int p = 0; p < parts; ++p) part(p);
}

bool coversWholeBuffer(const Framebuffer& fb, const RenderState& state) {
  const Rect r = clearRegion(fb, state);
  return r.x == 0 && r.y == 0 && r.width == fb.width() && r.height == fb.height();
}

}  // namespace

// A buffer that does not exist yet and that the clear writes whole is made unwritten (resize
// without a value: PixelVector), so that the clear writes each byte once, on all threads; any
// other is made as ensure* makes it.
void clearColor(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel) {
  const glm::dvec4 v(glm::clamp(value, 0.0f, 1.0f));
  const auto& mask = state.colorMask;
  const bool allChannels = mask[0] && mask[1] && mask[2] && mask[3];
  if (!fb.hasColor() && allChannels && coversWholeBuffer(fb, state)) fb.color().resize(fb.pixelCount());
  fb.ensureColor();
  glm::vec4* color = fb.color().data();
  if (allChannels) {
    const glm::vec4 written = writeColor(glm::vec4(0.0f), v, mask);  // no stored channel survives
    forEachClearedRun(fb, state, parallel, [&](size_t first, size_t count) { std::fill_n(color + first, count, written); });
    return;
  }
  forEachClearedRun(fb, state, parallel, [&](size_t first, size_t count) {
    for (size_t i = first; i < first + count; ++i) color[i] = writeColor(color[i], v, mask);
  });
}

void clearDepth(Framebuffer& fb, const RenderState& state, double value, const ParallelFor& parallel) {
  const uint32_t code = fb.depthCodec().encode(value);
  if (!fb.hasDepth() && state.depthWrite && coversWholeBuffer(fb, state)) fb.depthCodes().resize(fb.pixelCount());
  fb.ensureDepth();
  if (!state.depthWrite) return;
  uint32_t* depth = fb.depthCodes().data();
  forEachClearedRun(fb, state, parallel, [&](size_t first, size_t count) { std::fill_n(depth + first, count, code); });
}

void clearStencil(Framebuffer& fb, const RenderState& state, int value, const ParallelFor& parallel) {
  const uint8_t v = uint8_t(value & 0xFF);  // GL masks the clear value to the buffer's bits
  const uint8_t mask = state.stencil[FrontFacing].writeMask;
  if (!fb.hasStencil() && mask == 0xFF && coversWholeBuffer(fb, state)) fb.stencil().resize(fb.pixelCount());
  fb.ensureStencil();
  uint8_t* stencil = fb.stencil().data();
  forEachClearedRun(fb, state, parallel, [&](size_t first, size_t count) {
    if (mask == 0xFF) std::fill_n(stencil + first, count, v);
    else
      for (size_t i = first; i < first + count; ++i) stencil[i] = writeStencil(stencil[i], v, mask);
  });
}

void clearAccum(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel) {
  if (!fb.hasAccum() && coversWholeBuffer(fb, state)) fb.accum().resize(fb.pixelCount());
  fb.ensureAccum();
  const glm::vec4 v = glm::clamp(value, -1.0f, 1.0f);
  glm::vec4* accum = fb.accum().data();
  forEachClearedRun(fb, state, parallel, [&](size_t first, size_t count) { std::fill_n(accum + first, count, v); });
}

}  // namespace shadowref
