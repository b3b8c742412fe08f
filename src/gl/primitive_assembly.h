// Primitive assembly: a draw's indices become triangles, each triangle is clipped to a convex
// polygon, the polygon's facing decides culling, and its fan is set up ([GL 2.1, §2.6.1, §2.12,
// §2.14.1, §3.5.1]). These are the rules both pipelines follow: the reference
// (reference_pipeline.cpp) calls assembleTriangle for every triangle in order; the fast executor
// (exec/renderer.cpp) reproduces it with the same functions on many triangles at once.
#pragma once

#include <cstddef>
#include <vector>

#include "gl/clipper.h"
#include "gl/framebuffer.h"
#include "gl/pipeline.h"
#include "gl/raster_stats.h"
#include "gl/render_state.h"
#include "gl/triangle_setup.h"
#include "gl/vertex.h"

namespace shadowref {

// Guard band G (clipper.h) for a viewport: window coordinates stay within about 2^20 pixels, so
// fixed-point edge functions fit comfortably in 64 bits (triangle_setup.cpp, kMaxWindowCoordinate).
double guardBandFor(const Viewport& vp);

// The planes a draw is clipped against: near and far unless depth clamp turns them off
// (ARB_depth_clamp), far also off for the infinite projection (RenderState::clipFar), and the
// guard band of the viewport.
ClipPlanes clipPlanesFor(const RenderState& state);

// The rectangle of pixels a draw may touch: viewport, framebuffer and (if on) scissor. A pixel
// outside it produces no fragment: it is neither counted nor tested.
Rect drawRegion(const RenderState& state, const Framebuffer& fb);

// How many triangles a draw has: three indices each, or three vertices each without indices
// (a trailing one or two are ignored, as glDrawArrays ignores an incomplete triangle).
size_t trianglesOf(const DrawCall& call);

// Makes the buffers a draw needs, from the draw on: colour when a shader writes through a colour
// mask with a channel on, depth when the depth test is on, stencil when the stencil test is on.
// A buffer made here holds its initial value (framebuffer.cpp) until cleared.
void ensureBuffersFor(Framebuffer& fb, const DrawCall& call);

// Every index within the draw's vertices, or std::out_of_range before anything of the draw is
// assembled (GL leaves an index out of range undefined; shadowref refuses it).
void checkIndices(const DrawCall& call);

// The three vertices of triangle i of the draw.
void triangleVertices(const DrawCall& call, size_t i, const ClipVertex* out[3]);

// Rotates (a, b, c) so that the lexicographically smallest clip-space position comes first,
// keeping the winding. The same triangle then goes through clipping and setup with the same
// arithmetic however its vertices were listed, so a shadow volume's front cap gets bit-for-bit
// the depths of the scene pass.
void canonicalRotation(const ClipVertex*& a, const ClipVertex*& b, const ClipVertex*& c);

// What assembly of one triangle works in. `clipped` holds the vertices clipping made; the setups
// of a clipped triangle point into it (WindowVertex::source, for their varyings), so it must not
// change until they are rasterized: the next assembleTriangle refills it.
struct AssemblyScratch {
  std::vector<ClipVertex> polygon, clipped, clipScratch;
  std::vector<WindowVertex> window;
};

// Assembles one triangle into `setups` (cleared first): nothing when it is clipped away, culled or
// has no area; one setup when no vertex is outside a clip plane; otherwise the fan
// (p0, p_i, p_i+1) of the clipped polygon, every piece with the facing of the polygon as a whole
// ([GL 2.1, §2.14.1]: the sign of the polygon's area). Counts in `stats`: trianglesClipped (a
// vertex was outside a plane), trianglesCulled (the triangle or its clipped polygon has no area
// in fixed point, or is culled), trianglesRasterized (each setup made; a fan piece that snapping
// leaves without area, or a vertex beyond the fixed-point range, makes none and is counted
// nowhere).
void assembleTriangle(const ClipVertex* a, const ClipVertex* b, const ClipVertex* c, const RenderState& state,
                      const ClipPlanes& planes, int varyingCount, const DepthCodec& codec, AssemblyScratch& scratch,
                      std::vector<TriangleSetup>& setups, RasterStats& stats);

}  // namespace shadowref
