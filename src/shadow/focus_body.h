// The focus body of a trapezoidal shadow map: the part of the camera frustum where a shadow can
// be seen, i.e. the frustum ∩ the scene's bounding box ∩ the light's view volume.
//
// Why (found on the outdoor scene, see docs/shadow-maps.md): [Hempe 2004, §4.1.2] builds the
// trapezoid around the whole camera frustum. Outdoors, the upper half of the frustum is sky; a
// directional light projects those points far beyond the ground, outside the light's orthographic
// view of the scene, so a large part of the warped map held nothing (cleared to depth 1) and the
// trapezoid, stretched to include it, spent its texels on empty space. [Martin & Tan 2004, §4]
// "the eye's frustum ... as tight as possible") and LiSPSM's "body B" bound the frustum by the
// scene the same way. The trapezoid is then built around the body's vertices (focused_trapezoid.h).
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.h"

namespace shadowref {

// A plane n·p + d = 0; the inside is n·p + d ≥ 0.
struct HalfSpace {
  glm::dvec3 n{0.0};
  double d = 0.0;
  double signedDistance(const glm::dvec3& p) const { return glm::dot(n, p) + d; }
};

using ConvexPolygon = std::vector<glm::dvec3>;

// Sutherland–Hodgman: the part of a convex polygon inside one half-space.
ConvexPolygon clipPolygon(const ConvexPolygon& polygon, const HalfSpace& plane);

// A convex body as its faces and the half-spaces that bound it.
struct ConvexBody {
  std::vector<ConvexPolygon> faces;
  std::vector<HalfSpace> planes;
};

// A frustum-like hexahedron from its eight corners in frustumCorners order (near 0–3, far 4–7,
// each (left, bottom), (right, bottom), (right, top), (left, top)); half-spaces oriented to contain
// the corners' centroid.
ConvexBody hexahedron(const std::array<glm::dvec3, 8>& corners);
ConvexBody boxBody(const Aabb& box);
// The clip volume −w ≤ x, y, z ≤ w of a world -> clip matrix, in world space (its corners are the
// NDC cube's through the inverse).
ConvexBody clipVolumeBody(const glm::dmat4& worldToClip);

// The vertices of the intersection of convex bodies: every face of each body clipped by the
// half-spaces of all the others (each face of the intersection lies in a face of one of them).
// Empty when the intersection is empty (or has no area).
std::vector<glm::dvec3> intersectionVertices(const std::vector<ConvexBody>& bodies);

// The focus body's vertices: frustum ∩ scene box ∩ the light's clip volume (lightClip = P_light ·
// V_light, so a spot light's body lies in front of it).
std::vector<glm::dvec3> focusBody(const std::array<glm::dvec3, 8>& frustum, const Aabb& sceneBox,
                                  const glm::dmat4& lightClip);

}  // namespace shadowref
