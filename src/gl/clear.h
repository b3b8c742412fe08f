// glClear for each buffer, with GL's semantics: the scissor box limits it, and the colour mask,
// depth mask and (front) stencil write mask apply ([GL 2.1, §4.2.3]). Clearing allocates the
// buffer.
//
// A clear is made in two steps — prepareClear, which makes the buffers, and clearRows, which
// fills some of the rows — so that a renderer can fill each band of rows on the thread that draws
// into it next, right before it does (Renderer::clear): the band is then in that thread's cache.
#pragma once

#include <functional>
#include <optional>

#include <glm/glm.hpp>

#include "gl/framebuffer.h"
#include "gl/render_state.h"

namespace shadowref {

// Runs task(i) for i in [0, count) and returns when all are done, on several threads or on this
// one (the fast executor hands its thread pool, Renderer::parallelFor); an empty one: on this
// thread, in order, as the reference pipeline clears. What a clear's parts of rows are handed.
using ParallelFor = std::function<void(int count, const std::function<void(int)>& task)>;

// The pixels a clear or an accumulation operation touches: the buffer, cut to the scissor box.
Rect clearRegion(const Framebuffer& fb, const RenderState& state);

// What one glClear clears, and with which values; `state` gives the scissor box and the masks.
struct ClearRequest {
  RenderState state = {};
  std::optional<glm::vec4> color = std::nullopt;
  std::optional<double> depth = std::nullopt;
  std::optional<int> stencil = std::nullopt;
  std::optional<glm::vec4> accum = std::nullopt;
};

// Makes the buffers the request clears. A buffer that does not exist yet and that the clear
// writes whole is made unwritten (resize without a value: PixelVector), so that the clear writes
// each byte once, on whichever threads fill its rows; any other is made as ensure* makes it.
void prepareClear(Framebuffer& fb, const ClearRequest& request);
// Fills rows [y0, y1) of the request's region in every buffer it clears (after prepareClear).
void clearRows(Framebuffer& fb, const ClearRequest& request, int y0, int y1);
// Every row of the request's region (after prepareClear), cut into parts of rows that `parallel`
// may fill at once (every pixel is written by one part, so the bytes do not depend on the thread
// count).
void fillClear(Framebuffer& fb, const ClearRequest& request, const ParallelFor& parallel = {});
// prepareClear, then fillClear.
void clear(Framebuffer& fb, const ClearRequest& request, const ParallelFor& parallel = {});

void clearColor(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel = {});
void clearDepth(Framebuffer& fb, const RenderState& state, double value, const ParallelFor& parallel = {});
void clearStencil(Framebuffer& fb, const RenderState& state, int value, const ParallelFor& parallel = {});
void clearAccum(Framebuffer& fb, const RenderState& state, const glm::vec4& value, const ParallelFor& parallel = {});

}  // namespace shadowref
