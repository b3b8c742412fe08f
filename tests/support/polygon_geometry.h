// Independent double-precision geometry for coverage expectations: point in polygon by the
// crossing rule and distance to the polygon's edges. The tests use it to derive, without the
// rasterizer, which pixel centres a shape covers, leaving out centres too close to an edge to call.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace shadowref::testing {

using Polygon2 = std::vector<glm::dvec2>;

// Even-odd crossing test; the polygon may be given in either winding.
bool pointInPolygon(const Polygon2& polygon, const glm::dvec2& p);

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b);

// Smallest distance from p to any edge of the closed polygon.
double distanceToOutline(const Polygon2& polygon, const glm::dvec2& p);

// Expected coverage of one pixel centre: 1 inside, 0 outside, -1 when the centre lies within
// `margin` pixels of an edge (undecided: either answer is right).
int expectedCoverage(const Polygon2& polygon, const glm::dvec2& centre, double margin);

// The tolerance the coverage tests leave around edges: 1e-3 px for the decision itself plus half a
// sub-pixel step (2^-9 px), because the rasterizer snaps vertices to 1/256 pixel.
inline constexpr double kEdgeMargin = 1e-3 + 1.0 / 512.0;

}  // namespace shadowref::testing
