// Extrusion of silhouette edges to infinity ([Kuhn 2016, §3.4, §4.3.3]).
//
// A vertex V is sent away from the light to the point at infinity
//   V∞ = (V.xyz · L_w − L.xyz · V_w, 0)      ([Kuhn 2016, §3.4], with V_w = 1)
// L_w = 1 (point, spot): the direction from the light through V. L_w = 0 (directional, L.xyz
// towards the light): −L.xyz, the same point for every vertex, so the sides of a directional
// light's volume meet in one point at infinity. The infinite projection P_inf ([Kuhn 2016, §3.3])
// maps w = 0 points onto the far plane instead of clipping them.
//
// For a silhouette edge A -> B as it runs in its light-facing triangle (silhouette.h), the side
// quad B, A, D, C with D = A∞, C = B∞ has its normal pointing out of the volume
// ([Kuhn 2016, §4.3.3], lines 9-21): seen from outside it is counter-clockwise, like the front cap
// it continues.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shadow/silhouette.h"

namespace shadowref {

glm::dvec4 extrudeToInfinity(const glm::dvec3& vertex, const glm::dvec4& light);

// The side quad of one silhouette edge: {B, A, D, C}, in that order.
std::array<glm::dvec4, 4> sideQuad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec4& light);

// Where a volume's vertex list keeps the points at infinity: after the mesh's welded vertices,
// one per vertex for a point light, or a single shared one for a directional light (all V∞ are
// equal there, and sharing the index keeps the volume a closed mesh by index).
struct InfiniteIndexing {
  uint32_t base = 0;     // index of the first point at infinity
  bool shared = false;   // directional light: every vertex goes to `base`
  uint32_t operator()(uint32_t vertex) const { return shared ? base : base + vertex; }
};

// The triangles of quad {B, A, D, C} as indices: (B, A, D) and (B, D, C), both wound like the
// quad. For a directional light D = C and the second triangle has no area: only (B, A, D).
void appendSideTriangles(const SilhouetteEdge& edge, const InfiniteIndexing& infinite,
                         std::vector<glm::uvec3>& out);

}  // namespace shadowref
