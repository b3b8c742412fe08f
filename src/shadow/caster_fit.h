// A directional light's orthographic map fitted to what can be seen shadowed, instead of to the
// whole scene's box ([Hempe 2004, §5.1.2] fits glOrtho to the scene; a large ground slab then
// spreads the map's texels over ground no caster shadows).
//
// The fit is the usual one for directional lights: the projection fitted to what the camera sees
// (the view frustum ∩ the scene, the body B of the focus body of TSM, [Martin & Tan 2004, §4]: "as
// tight as possible"), the near plane pulled towards the light so that every caster in front of
// it stays in the map; here narrowed to the casters that can shadow that body:
//   1. receivers: every instance's box ∩ the camera frustum (far plane fitted to the scene); the
//      bounds of each part that is not empty;
//   2. a caster (an instance with a shadow mesh, within the light's range) can shadow a receiver
//      only if its box, swept along the light's direction, overlaps the receiver's visible part
//      with positive volume (a slab under the houses cannot shadow them; the houses standing on
//      it touch it only in a plane). A caster and its own receiver part: a mesh that is its own
//      shadow mesh and convex shadows only its own faces turned from the light, so only when one
//      of those faces is turned to the camera; any other instance is taken to shadow itself;
//   3. the map's x-y rectangle in light eye space: the union of the relevant casters' boxes, each
//      cut to the rectangle of the visible part of the scene (frustum ∩ scene box), widened by
//      kFitMarginTexels texels on each side (a PCF kernel at the edge reads rendered texels);
//      its depth range: from the nearest relevant caster to the farthest visible point. The light
//      view is first turned about its axis so that the rectangle around the casters' footprint is
//      the smallest ([Freeman & Shapira 1975]).
// Every visible point a caster shadows lies in the caster's x-y footprint and in the visible
// rectangle, so it lies in the map, and so does the part of the caster in front of it. A visible
// point outside the map is shadowed by no caster: the lookup calls it lit (ShadowLookup::outsideLit).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shadow/light_view.h"

namespace shadowref {

// Texels of margin around the fitted rectangle on each side, on top of half the PCF kernel.
inline constexpr int kFitMarginTexels = 1;
// Meshes with more triangles are not tested for convexity (the test is triangles × vertices) and
// are taken to shadow themselves.
inline constexpr size_t kMaxConvexityTestTriangles = 512;

struct CasterFit {
  LightView view;
  bool fitted = false;          // false: no caster shadows a visible receiver (view = the scene box's)
  std::vector<size_t> casters;  // the relevant casters (indices into the instances), ascending
};

// The fit described above for a directional light. `frustum`: the camera's eight corners
// (frustumCorners order), `eye` its position; `pcf` the kernel size the map is looked up with;
// `mapSize` its texels per side.
CasterFit fitDirectionalToCasters(const Light& light, const std::vector<Instance>& instances, const Aabb& sceneBox,
                                  const std::array<glm::dvec3, 8>& frustum, const glm::dvec3& eye, int mapSize,
                                  int pcf);

// Whether the box `caster`, swept from where it is along `direction` to infinity, overlaps
// `receiver` by more than `tolerance` in every axis (touching boxes do not).
bool sweptBoxOverlaps(const Aabb& caster, const glm::dvec3& direction, const Aabb& receiver, double tolerance);

// Whether every vertex of the mesh lies on the inner side of every triangle's plane (within a
// relative 1e-9 of the mesh's size): a convex mesh, whose points are shadowed by the mesh itself
// only on faces turned from the light. Meshes of more than kMaxConvexityTestTriangles: false.
bool isConvexMesh(const Mesh& mesh);

}  // namespace shadowref
