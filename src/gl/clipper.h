// Homogeneous clipping before the perspective divide ([GL 2.1, §2.12]).
//
// Planes, in this fixed order: near z >= -w, far z <= w (optional), a guard band
// |x|, |y| <= G w that keeps window coordinates inside the fixed-point range of the rasterizer,
// and w >= w_min so that nothing is ever divided by zero. Inside the guard band nothing is cut at
// the viewport edges, so ordinary triangles keep their exact vertices; pixels outside the viewport
// are simply never visited.
//
// Watertightness: an edge shared by two triangles is cut at the same point in both, because the
// intersection is always computed from the inside end towards the outside end and depends on
// nothing else. Vertices with w = 0 (points at infinity, P_inf) are ordinary input.
#pragma once

#include <vector>

#include "gl/vertex.h"

namespace shadowref {

struct ClipPlanes {
  bool nearPlane = true;
  bool farPlane = true;
  double guardBand = 1 << 16;  // G: |x|, |y| <= G w
};

// The smallest w a clipped vertex may have. The near plane already keeps w >= near > 0 for
// perspective projections; this plane only matters with depth clamp (near plane off) and for
// degenerate points at infinity on the view axis.
inline constexpr double kMinClipW = 1e-30;

// Clips the convex polygon `in` (3 vertices for a triangle) and writes the result to `out`
// (cleared first). Fewer than 3 output vertices means nothing is left. `varyingCount` limits the
// interpolation work to the varyings in use.
void clipPolygon(const std::vector<ClipVertex>& in, const ClipPlanes& planes, int varyingCount,
                 std::vector<ClipVertex>& out, std::vector<ClipVertex>& scratch);

// True when every vertex is inside every plane: the common case, no clipping needed.
bool insideAllPlanes(const ClipVertex* v, int count, const ClipPlanes& planes);

}  // namespace shadowref
