// One light's shadow maps and their lookup (002 §3.1, §4.1, §5.1; SPEC.md §4): step 1 of a
// shadow-mapped frame, and the shadow test step 2 applies to each fragment's world position.
//   - directional light: one orthographic map fitted to the scene's bounding box;
//   - spot light: one perspective map along its axis (light_view.h);
//   - point light (beyond the documents): six perspective cube-face maps;
//   - trapezoidal (directional and spot): the light's clip space warped by N_T (002 §4.1.2),
//     the trapezoid built around the focus body, the camera frustum ∩ the scene (focus_body.h).
// Against self-shadowing (002 §3.2): polygon offset or back faces only in the map pass, or a
// constant bias in the comparison (shadow_lookup.h).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "raster/depth_compare_sampler.h"
#include "raster/raster_stats.h"
#include "scene/scene.h"
#include "shadow/light_view.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_lookup.h"
#include "shadow/trapezoid.h"

namespace shadowref {

struct LightShadow {
  Light light;
  bool cube = false;
  std::array<DepthTexture, 6> textures;  // [0] only, unless cube
  std::array<LightView, 6> views;        // the unwarped light view(s), as the textures
  ShadowLookup lookup;                   // the map's lookup (T with N_T for TSM)
  CubeShadowLookup cubeLookup;
  bool trapezoidal = false;
  Trapezoid trapezoid;                   // with trapezoidal: its corners, η, N_T
  std::vector<glm::dvec3> focusBody;     // with trapezoidal: the body's vertices (world)

  LightShadow() = default;
  LightShadow(const LightShadow&) = delete;  // the lookups point into `textures`
  LightShadow& operator=(const LightShadow&) = delete;

  // 1 where lit, the compare-fail value where shadowed, between them at PCF edges.
  double factor(const glm::dvec3& worldPosition) const { return cube ? cubeLookup.factor(worldPosition) : lookup.factor(worldPosition); }
  int mapCount() const { return cube ? 6 : 1; }
};

// The world box the maps are fitted to: every instance's bounds.
Aabb sceneBounds(const std::vector<Instance>& instances);

// Renders `light`'s map(s) with the scene's ShadowSettings and sets up the lookup. `trapezoidal`
// selects TSM for directional and spot lights (point lights always get cube maps). Raster work
// adds to `stats`.
std::unique_ptr<LightShadow> buildLightShadow(const Scene& scene, const std::vector<Instance>& instances,
                                              const SceneView& view, const Light& light, bool trapezoidal,
                                              int threads, RasterStats& stats);

// Step 1 alone: depth from the light into a size × size map through `view` and `projection`
// (P_light, or N_T · P_light for TSM, 002 Listing 11). Casters are the instances' shadow meshes
// (the low-poly proxy where given, 004) within the light's range.
DepthTexture renderDepthMap(const Scene& scene, const std::vector<Instance>& instances, const Light& light,
                            const glm::dmat4& view, const glm::dmat4& projection, int threads, RasterStats& stats);

}  // namespace shadowref
