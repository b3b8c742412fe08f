// The per-fragment operations applied to one fragment, in GL order ([GL 2.1, §4.1]): scissor ->
// stencil test -> depth test -> stencil update -> depth write -> shading -> blend -> masked colour
// write. Each step is one function of fragment_ops.h; processFragment is the sequence, and
// records the pixel history's FragmentEvent at the watched pixel. The fast executor's one-fragment
// path (FragmentProcessor::process: the watched pixel) calls it; its span loops give the same bytes.
#pragma once

#include "gl/coverage.h"
#include "gl/fragment_observer.h"
#include "gl/fragment_shader.h"
#include "gl/framebuffer.h"
#include "gl/raster_stats.h"
#include "gl/render_state.h"
#include "gl/triangle_setup.h"

namespace shadowref {

// Which buffers a draw's fragments read and write. With the depth test off, or no depth buffer,
// the test passes and the depth buffer is not written ([GL 2.1, §4.1.6]); with the stencil test
// off it neither tests nor writes ([GL 2.1, §4.1.5]); colour is written only by a shader through a
// colour mask with a channel on (a draw without a shader is stencil or depth only).
struct BufferUse {
  bool writesColor = false, usesDepth = false, writesDepth = false, usesStencil = false;
};
BufferUse bufferUse(const Framebuffer& fb, const RenderState& state, const FragmentShader* shader);

// One fragment at covered pixel `p` of triangle `t` through the per-fragment operations. Counts
// in `stats`: fragments (every call that passes the scissor test), stencilFailed, depthFailed,
// stencilWrites (the stored stencil byte changed), colorWrites (the colour buffer was written,
// even if with the same value). The shader runs only for a fragment that passed both tests and
// writes colour. `watch`: the event is reported when (p.x, p.y) is the watched pixel.
void processFragment(Framebuffer& fb, const RenderState& state, const FragmentShader* shader, const BufferUse& use,
                     const TriangleSetup& t, const CoveredPixel& p, RasterStats& stats, const PixelWatch* watch);

}  // namespace shadowref
