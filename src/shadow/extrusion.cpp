#include "shadow/extrusion.h"

namespace shadowref {

glm::dvec4 extrudeToInfinity(const glm::dvec3& vertex, const glm::dvec4& light) {
  return glm::dvec4(vertex * light.w - glm::dvec3(light), 0.0);
}

std::array<glm::dvec4, 4> sideQuad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec4& light) {
  return {glm::dvec4(b, 1.0), glm::dvec4(a, 1.0), extrudeToInfinity(a, light), extrudeToInfinity(b, light)};
}

// The quad is split along the diagonal from the finite vertex with the LARGER index to the point
// at infinity of the smaller one, whichever way the edge runs. The edge shared by two light-facing
// triangles then gives the same two triangles in both per-triangle volumes (buildTriangleVolumes),
// only wound the other way: they rasterize to the same fragments with the same depths and cancel
// exactly. With the diagonal B-D for both orientations the two quads were cut along different
// diagonals (B-A∞ and A-B∞) and interpolated depths differing in the last bit broke the
// cancellation where the quad meets the surface (pumpkins, pixel 129,156 at 200x160).
void appendSideTriangles(const SilhouetteEdge& edge, const InfiniteIndexing& infinite,
                         std::vector<glm::uvec3>& out) {
  const uint32_t b = edge.b, a = edge.a, d = infinite(edge.a), c = infinite(edge.b);
  if (d == c) {  // directional light: one triangle
    out.push_back({b, a, d});
  } else if (a < b) {  // diagonal B-D
    out.push_back({b, a, d});
    out.push_back({b, d, c});
  } else {  // diagonal A-C
    out.push_back({b, a, c});
    out.push_back({a, d, c});
  }
}

}  // namespace shadowref
