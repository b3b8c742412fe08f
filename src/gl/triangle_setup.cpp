#include "gl/triangle_setup.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace shadowref {

namespace {

// The largest window coordinate, in pixels, a triangle may have. The clipper's guard band keeps
// every clipped vertex within about 2^19 pixels of the viewport (guardBandFor), so this bound is
// never reached by a finite triangle; at it, fixed-point differences stay below 2^29, their
// products below 2^58, and the facing sum over a clipped polygon (at most 8 triangles) below 2^62:
// no int64_t arithmetic of setup or rasterization can overflow.
constexpr double kMaxWindowCoordinate = 1 << 20;

// To 1/256 pixel, saturating: a coordinate beyond +-kMaxWindowCoordinate (or NaN, which only a
// non-finite input makes) becomes the bound instead of an undefined double -> int64_t
// conversion. setupTriangle then rejects the triangle.
int64_t snap(double windowCoordinate) {
  constexpr double kLimit = kMaxWindowCoordinate * double(kSubpixelOne);
  const double fixed = std::floor(windowCoordinate * double(kSubpixelOne) + 0.5);
  if (fixed >= -kLimit && fixed <= kLimit) return int64_t(fixed);
  return fixed > 0.0 ? int64_t(kLimit) : -int64_t(kLimit);
}

// Whether the vertex's window position lies within the fixed-point range (so its snapped
// coordinates are exact, not saturated) and its depth and 1/w are finite.
bool representable(const WindowVertex& v) {
  return std::fabs(v.fx) <= kMaxWindowCoordinate && std::fabs(v.fy) <= kMaxWindowCoordinate && std::isfinite(v.z) &&
         std::isfinite(v.invW);
}

// Top-left rule in a y-up window: a pixel centre exactly on an edge belongs to the triangle when
// the edge is a left edge (runs downwards in a counter-clockwise triangle) or a top edge
// (horizontal, runs right-to-left, interior below).
bool isTopLeft(int64_t dx, int64_t dy) { return dy < 0 || (dy == 0 && dx < 0); }

// First pixel whose centre is >= the fixed-point coordinate, and last whose centre is <= it.
int firstPixelAtOrAfter(int64_t fixed) {
  const int64_t t = fixed - kSubpixelHalf;
  return int(t >= 0 ? (t + kSubpixelOne - 1) / kSubpixelOne : -((-t) / kSubpixelOne));
}
int lastPixelAtOrBefore(int64_t fixed) {
  const int64_t t = fixed - kSubpixelHalf;
  return int(t >= 0 ? t / kSubpixelOne : -((-t + kSubpixelOne - 1) / kSubpixelOne));
}

// The depth plane's slopes from the unsnapped window coordinates; from the snapped ones when the
// unsnapped triangle has no area in double precision (a sliver that snapping opened up).
void computeDepthPlane(TriangleSetup& t) {
  double x1 = t.v[1].fx - t.v[0].fx, y1 = t.v[1].fy - t.v[0].fy;
  double x2 = t.v[2].fx - t.v[0].fx, y2 = t.v[2].fy - t.v[0].fy;
  double det = x1 * y2 - x2 * y1;
  if (!(det > 0.0)) {  // not counter-clockwise in double (or NaN): use the snapped vertices
    const double s = 1.0 / double(kSubpixelOne);
    x1 = double(t.v[1].x - t.v[0].x) * s;
    y1 = double(t.v[1].y - t.v[0].y) * s;
    x2 = double(t.v[2].x - t.v[0].x) * s;
    y2 = double(t.v[2].y - t.v[0].y) * s;
    det = x1 * y2 - x2 * y1;
    t.v[0].fx = double(t.v[0].x) * s;  // the plane then passes through the snapped vertex 0
    t.v[0].fy = double(t.v[0].y) * s;
  }
  const double z1 = t.v[1].z - t.v[0].z, z2 = t.v[2].z - t.v[0].z;
  t.dzdx = (z1 * y2 - z2 * y1) / det;
  t.dzdy = (x1 * z2 - x2 * z1) / det;
}

// Whether every depth computed at a covered pixel centre lies in (0, 1]. The covered centres lie
// in the snapped triangle, over which the (linear) plane takes its extremes at the snapped
// vertices; a computed depth (planeDepthAt's operations, or the span loops' same ones split by
// row) differs from the exact plane by a few rounding errors of its terms, about 6 * 2^-53 of the
// sum of their magnitudes: far inside the margin of 2^-40 of that sum. Infinite or NaN terms give
// false.
bool depthsInUnit(const TriangleSetup& t) {
  const double fx0 = t.v[0].fx, fy0 = t.v[0].fy, z0 = t.v[0].z, s = 1.0 / double(kSubpixelOne);
  double lo = 1.0, hi = 0.0, dx = 0.0, dy = 0.0;
  for (const WindowVertex& v : t.v) {
    const double x = double(v.x) * s - fx0, y = double(v.y) * s - fy0;
    const double z = (z0 + (t.dzdx * x + t.dzdy * y)) + t.depthOffset;
    lo = std::min(lo, z);
    hi = std::max(hi, z);
    dx = std::max(dx, std::fabs(x));
    dy = std::max(dy, std::fabs(y));
  }
  const double size = std::fabs(z0) + std::fabs(t.dzdx) * dx + std::fabs(t.dzdy) * dy + std::fabs(t.depthOffset);
  const double margin = size * 0x1p-40;
  return lo - margin > 0.0 && hi + margin <= 1.0;
}

}  // namespace

WindowVertex toWindow(const ClipVertex& v, const Viewport& vp) {
  const double invW = 1.0 / v.position.w;
  const double xn = v.position.x * invW, yn = v.position.y * invW, zn = v.position.z * invW;
  WindowVertex w;
  w.fx = double(vp.x) + (xn + 1.0) * 0.5 * double(vp.width);
  w.fy = double(vp.y) + (yn + 1.0) * 0.5 * double(vp.height);
  w.x = snap(w.fx);
  w.y = snap(w.fy);
  w.z = vp.nearVal + (zn + 1.0) * 0.5 * (vp.farVal - vp.nearVal);
  w.invW = invW;
  w.source = &v;
  return w;
}

Facing facingOf(int64_t area2, FrontFace frontFace) {
  const bool ccw = area2 > 0;
  return (ccw == (frontFace == FrontFace::CCW)) ? FrontFacing : BackFacing;
}

bool isCulled(Facing facing, CullMode cull) {
  switch (cull) {
    case CullMode::None: return false;
    case CullMode::Front: return facing == FrontFacing;
    case CullMode::Back: return facing == BackFacing;
    case CullMode::FrontAndBack: return true;
  }
  return false;
}

bool setupTriangle(const WindowVertex& a, const WindowVertex& b, const WindowVertex& c, Facing facing,
                   const RenderState& state, const DepthCodec& codec, TriangleSetup& t) {
  // A vertex made from non-finite or out-of-range input has saturated coordinates: no pixel of
  // such a triangle would be right, so it is dropped as a triangle without area is.
  if (!representable(a) || !representable(b) || !representable(c)) return false;
  int64_t area2 = signedArea2(a, b, c);
  if (area2 == 0) return false;
  t.v[0] = a;
  t.v[1] = b;
  t.v[2] = c;
  if (area2 < 0) {
    std::swap(t.v[1], t.v[2]);
    area2 = -area2;
  }
  t.area2 = area2;
  t.facing = facing;
  for (int i = 0; i < 3; ++i) {
    const WindowVertex& p = t.v[(i + 1) % 3];
    const WindowVertex& q = t.v[(i + 2) % 3];
    const int64_t dx = q.x - p.x, dy = q.y - p.y;
    t.stepX[i] = -dy * kSubpixelOne;
    t.stepY[i] = dx * kSubpixelOne;
    t.bias[i] = isTopLeft(dx, dy) ? 0 : -1;
  }
  const int64_t x0 = std::min({t.v[0].x, t.v[1].x, t.v[2].x});
  const int64_t x1 = std::max({t.v[0].x, t.v[1].x, t.v[2].x});
  const int64_t y0 = std::min({t.v[0].y, t.v[1].y, t.v[2].y});
  const int64_t y1 = std::max({t.v[0].y, t.v[1].y, t.v[2].y});
  t.minX = firstPixelAtOrAfter(x0);
  t.maxX = lastPixelAtOrBefore(x1);
  t.minY = firstPixelAtOrAfter(y0);
  t.maxY = lastPixelAtOrBefore(y1);
  computeDepthPlane(t);
  t.depthOffset = state.polygonOffset.enabled ? polygonOffset(t, state.polygonOffset, codec) : 0.0;
  // Asked only where the row loops read it and its cost (three vertices) can be won back: leaving
  // out the clamp saves four of about 28 instructions per eight pixels.
  const int64_t boxPixels = int64_t(t.maxX - t.minX + 1) * int64_t(t.maxY - t.minY + 1);
  t.depthsInUnit = plainFloatDepths(codec, state.depthClamp) && boxPixels >= 256 && depthsInUnit(t);
  return true;
}


double polygonOffset(const TriangleSetup& t, const PolygonOffset& po, const DepthCodec& codec) {
  const double m = std::max(std::fabs(t.dzdx), std::fabs(t.dzdy));
  const double zMax = std::clamp(std::max({t.v[0].z, t.v[1].z, t.v[2].z}), 0.0, 1.0);
  return po.factor * m + po.units * codec.resolvableDifference(zMax);
}

}  // namespace shadowref
