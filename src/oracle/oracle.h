// An independent oracle for the stencil shadow volumes: a ray caster that does not use the
// rasterizer. For every pixel centre it finds the first hit of the primary ray (own BVH, double
// precision), counts the signed crossings of the shadow-volume polygons along the ray in exact
// projective form, and casts a shadow ray to the light.
//
//   zpass: crossings of what z-pass draws — the volume SIDES, and the front caps of the meshes
//          the volumes do not cast as written (shadow/volume_casting.h) — from the near plane to
//          the hit, +1 entering through a front face, -1 leaving through a back face: what z-pass
//          counts with INCR on front and DECR on back faces where the depth test passes
//          ([Kuhn 2016, §3.1]). The ray starts on the near plane because the rasterizer clips what
//          lies before it.
//   The primary ray's hit is the first FRONT face (of the render meshes), as the scene pass culls
//   back faces: through an open roof from inside, the ray goes on to what is beyond it.
//   zfail: crossings of sides and caps from the hit to infinity, +1 for back faces, -1 for front
//          faces — what z-fail counts where the depth test fails ([Kuhn 2016, §3.4]). A front cap
//          lying in the hit surface counts here, as its fragments fail LESS against the equal scene
//          depth; a back cap at infinity counts, as P_inf puts it at depth 1 ([Kuhn 2016, §3.3]).
//   Without a hit (background) the hit is at infinity: zpass takes every finite crossing, zfail
//   only those at infinity.
// For closed volumes zfail is the number of volumes containing the hit point; zpass equals it when
// the near-plane point of the pixel lies outside every volume, and otherwise falls short by the
// number of volumes containing that point (the camera-in-shadow failure of z-pass,
// [Kuhn 2016, §3.4]).
//
//   lit: 1 when a shadow ray from the hit to the light meets no shadow-casting geometry (the
//        instances' shadowMesh, within range, every triangle two-sided), 0 otherwise; 0 without
//        a hit.
//   nearEdge: pixels a comparison with the rasterizer may leave out: within one pixel of a
//        projected contour edge of the geometry or of a volume (edges whose two triangles face the
//        eye differently, open and non-manifold edges), pixels whose hit lies within a relative
//        1e-6 of a volume crossing (depth too close to call), and pixels whose hit instance,
//        zpass or zfail differs from a 4-neighbour's (a shadow outline or an object boundary within
//        one pixel).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace shadowref::oracle {

struct OracleOptions {
  bool forceInfiniteProjection = false;  // as makeCameraView's flag
  bool respectRange = true;              // light range culling of casters ([Kuhn 2016, §4.3.1])
  double edgeRadius = 1.0;               // pixels
  double depthAmbiguity = 1e-6;          // relative distance along the ray
  bool markNeighbourChanges = true;
  int threads = 0;                       // 0: hardware concurrency; results never depend on it
};

struct OracleImage {
  int width = 0, height = 0;
  // Per pixel, index y * width + x, row 0 at the bottom (as the framebuffer).
  std::vector<int> zpass, zfail;
  std::vector<uint8_t> lit, hitMask, nearEdge;
  std::vector<int> hitInstance;          // index into Scene::instances(), -1 without a hit
  std::vector<uint32_t> hitTriangle;     // index into that instance's mesh triangles; 0 without a hit
  std::vector<glm::dvec3> hitPoint;      // world space; 0 without a hit

  size_t index(int x, int y) const { return static_cast<size_t>(y) * width + x; }
};

OracleImage castOracle(const Scene& scene, const Light& light, const OracleOptions& options = {});

// The world plane (trianglePlane, shadow/shadow_lookup.h) of each pixel's hit triangle, (0, 0, 0,
// 0) without a hit: what a shadow-map lookup with receiver-plane depth bias follows there.
// `instances`: the scene's, as castOracle numbered them (Scene::instances()).
std::vector<glm::dvec4> hitPlanes(const OracleImage& image, const std::vector<Instance>& instances);

}  // namespace shadowref::oracle
