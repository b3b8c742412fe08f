// Triangle setup: viewport transform, snapping to fixed point, facing, and the edge functions the
// rasterizer walks.
//
// Window coordinates are snapped to 1/256 pixel (kSubpixelBits = 8) and every coverage decision
// is made in exact 64-bit integer arithmetic, so two triangles that share an edge see the same
// edge function with opposite sign, and the top-left rule gives each pixel centre on it to
// exactly one of them: watertight, which stencil counting depends on.
#pragma once

#include <cstdint>

#include "gl/framebuffer.h"
#include "gl/render_state.h"
#include "gl/vertex.h"

namespace shadowref {

inline constexpr int kSubpixelBits = 8;
inline constexpr int64_t kSubpixelOne = int64_t(1) << kSubpixelBits;
inline constexpr int64_t kSubpixelHalf = kSubpixelOne / 2;

struct WindowVertex {
  int64_t x = 0, y = 0;  // fixed point, 1/256 pixel
  double fx = 0.0, fy = 0.0;  // the same before snapping: the depth plane is built from these
  double z = 0.0;        // window depth (glDepthRange applied), unclamped
  double invW = 0.0;     // 1 / w_clip, for perspective-correct varyings
  const ClipVertex* source = nullptr;
};

// Clip space -> window space for one vertex ([GL 2.1, §2.11.1]). Requires w > 0.
WindowVertex toWindow(const ClipVertex& v, const Viewport& vp);

// Twice the signed area in fixed-point units; > 0 is counter-clockwise (row 0 at the bottom).
inline int64_t signedArea2(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

Facing facingOf(int64_t signedArea2, FrontFace frontFace);
bool isCulled(Facing facing, CullMode cull);

// Edge i runs from vertex (i+1)%3 to (i+2)%3, opposite vertex i. Its function at a sample point
// p is E_i(p) = dx * (p.y - y_j) - dy * (p.x - x_j); positive inside a counter-clockwise
// triangle, and E_0 + E_1 + E_2 = area2 everywhere, so lambda_i = E_i / area2.
struct TriangleSetup {
  WindowVertex v[3];       // counter-clockwise
  int64_t area2 = 0;       // > 0
  Facing facing = FrontFacing;
  int64_t stepX[3]{}, stepY[3]{};  // change of E_i for one pixel right / up
  // The top-left rule as decided here (isTopLeft, triangle_setup.cpp): 0 for a top or left edge,
  // -1 otherwise. Consumed by coverage (coverage.h, covers): E_i + bias_i >= 0 covers.
  int64_t bias[3]{};
  int minX = 0, minY = 0, maxX = -1, maxY = -1;  // pixels whose centres may be covered
  double depthOffset = 0.0;
  // Window depth as a plane through the UNSNAPPED vertices, as GL implementations compute it
  // (snapping moves a vertex by up to 1/512 pixel; on a steep plane that would be hundreds of
  // 24-bit depth units): z(x, y) = z0 + dzdx (x - fx0) + dzdy (y - fy0) at pixel centres.
  double dzdx = 0.0, dzdy = 0.0;
  // Every depth computed at a covered pixel centre (with the offset, before any clamp) is in
  // (0, 1], so that the depth codec's clamp changes none: set for triangles of 256 pixels and
  // more (their span loops leave the clamp out), false where not shown or not asked.
  bool depthsInUnit = false;

  // E_i at the centre of pixel (px, py). Inline: the span loops ask for three at every triangle
  // and band.
  int64_t edgeAt(int i, int px, int py) const {
    constexpr int kNext[3] = {1, 2, 0}, kAfter[3] = {2, 0, 1};  // (i + 1) % 3, (i + 2) % 3
    const WindowVertex& a = v[kNext[i]];
    const WindowVertex& b = v[kAfter[i]];
    const int64_t sx = int64_t(px) * kSubpixelOne + kSubpixelHalf;
    const int64_t sy = int64_t(py) * kSubpixelOne + kSubpixelHalf;
    return (b.x - a.x) * (sy - a.y) - (b.y - a.y) * (sx - a.x);
  }
};

// The pixels a setup may cover (its minX … maxY), in a compact list beside the setups: the
// flush's loops (a draw's rows, the bands' work estimate) and each band's choice of its setups
// read 16 bytes a triangle instead of a line of a few-hundred-byte setup another thread wrote.
struct SetupBounds {
  int minX, minY, maxX, maxY;
};

// The setups of a block of triangles, set up in place: emplace_back() leaves the setup
// unconstructed (no zero-fill of a few hundred bytes that setupTriangle writes again).
using SetupBlock = std::vector<TriangleSetup, ConstructLaterAllocator<TriangleSetup>>;

// Whether the span loops compute a triangle's depths as plain floats, whose clamp to [0, 1]
// depthsInUnit may leave out: a Float32 buffer without depth clamp (a Unorm24 code is rounded lane
// by lane, a depth clamp clamps to the depth range). Set-up asks depthsInUnit only there.
inline bool plainFloatDepths(const DepthCodec& codec, bool depthClamp) {
  return codec.format == DepthFormat::Float32 && !depthClamp;
}

// Builds the setup of a window-space triangle with the given facing. Returns false when the
// snapped triangle has no area, or when a vertex lies beyond the fixed-point range (only
// non-finite or absurdly large input gets there; see snap). Vertex order is made
// counter-clockwise here.
bool setupTriangle(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, Facing facing,
                   const RenderState& state, const DepthCodec& codec, TriangleSetup& out);

// Window depth of the triangle's plane at the centre of pixel (px, py), before offset.
inline double planeDepthAt(const TriangleSetup& t, int px, int py) {
  const double cx = double(px) + 0.5, cy = double(py) + 0.5;
  return t.v[0].z + (t.dzdx * (cx - t.v[0].fx) + t.dzdy * (cy - t.v[0].fy));
}

// GL 1.1 polygon offset: factor * max(|dz/dx|, |dz/dy|) + units * r.
double polygonOffset(const TriangleSetup& t, const PolygonOffset& po, const DepthCodec& codec);

}  // namespace shadowref
