// Coverage ([GL 2.1, §3.5.1]): which pixels a set-up triangle makes fragments at. A pixel is
// covered when its centre (x + 1/2, y + 1/2) satisfies E_i + bias_i >= 0 for all three edge
// functions of the setup (triangle_setup.h), evaluated exactly in 64-bit fixed point.
//
// This is where the top-left rule is CONSUMED: triangle_setup.cpp (isTopLeft) decides each edge's
// bias — 0 for a top or left edge, -1 otherwise — and this test applies it. A centre exactly on an
// edge shared by two triangles has E = 0 in one and E = 0 (the same edge, reversed) in the other,
// and exactly one of them has the edge as top-left, so the centre is covered once: no gap and no
// double count, which stencil shadow counting relies on.
#pragma once

#include <cstdint>
#include <vector>

#include "gl/render_state.h"
#include "gl/triangle_setup.h"

namespace shadowref {

// A covered pixel and its three edge values there, unbiased (E_i, not E_i + bias_i): they are the
// barycentric weights times area2 that the fragment stage interpolates with.
struct CoveredPixel {
  int x = 0, y = 0;
  int64_t e[3]{};
};

// Whether the centre of pixel (x, y) is covered; writes the unbiased edge values to `e`.
bool covers(const TriangleSetup& t, int x, int y, int64_t e[3]);

// The pixels to test: the setup's bounds (the pixels whose centres may lie inside its snapped
// vertices' box) cut to the draw region (drawRegion, primitive_assembly.h). Empty when they miss.
Rect candidatePixels(const TriangleSetup& t, const Rect& region);

// Every covered pixel of the triangle inside `region`, row by row from the bottom, left to right
// (appended to `out`, which is cleared first). The order is the reference's; no byte depends on
// it, since a triangle covers each pixel at most once.
void coveredPixels(const TriangleSetup& t, const Rect& region, std::vector<CoveredPixel>& out);

}  // namespace shadowref
