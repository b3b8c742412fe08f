// Which triangles of a mesh face the light ([Kuhn 2016, §3.5, §4.3.4]; [DSS article] "d = n·l").
//
// A triangle faces the light when the light lies strictly on the outer side of its plane:
//   N · (L.xyz − L.w · V) > 0
// with N the outward face normal, V any vertex of the triangle and L the homogeneous light.
// For a point or spot light (L.w = 1) this is N · (L − V) > 0 ([Kuhn 2016, §4.3.4]); for a
// directional light (L.w = 0, L.xyz the direction TOWARDS the light) it is N · L > 0. One formula,
// both cases. A light exactly in the triangle's plane does not face it (strict inequality).
// [Kuhn 2016, §4.3.4] marks a triangle back-facing when N · (L − V) < 0, so a tie faces there; here
// it does not, so that a face parallel to a directional light is never a silhouette side.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/mesh.h"

namespace shadowref {

bool facesLight(const glm::dvec3& normal, const glm::dvec3& vertex, const glm::dvec4& light);

// facing[t] = 1 when welded triangle t faces `light` (object space, as the mesh), else 0.
// V is the triangle's first welded corner, as [Kuhn 2016, §4.3.4] takes vertex A. `facing` is
// resized, so a reused vector allocates only the first time.
void computeFacing(const Mesh& mesh, const glm::dvec4& light, std::vector<uint8_t>& facing);

// The light in an instance's object space: inverse(world) · L. Points (w = 1) and directions
// (w = 0) transform alike as homogeneous vectors; the facing test is a plane-side test, which any
// affine map preserves, so facing in object space equals facing in world space.
glm::dvec4 lightInObjectSpace(const glm::dmat4& world, const glm::dvec4& worldLight);

}  // namespace shadowref
