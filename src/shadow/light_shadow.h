// One light's shadow maps and their lookup ([Hempe 2004, §3.1, §4.1, §5.1]): step 1 of a
// shadow-mapped frame, and the shadow test step 2 applies to each fragment's world position.
//   - directional light: one orthographic map fitted to the casters that can shadow what the
//     camera sees (caster_fit.h), a point outside it lit; for TSM fitted to the scene's box;
//   - spot light: one perspective map along its axis (light_view.h);
//   - point light (beyond the documents): six perspective cube-face maps;
//   - trapezoidal (directional and spot): the light's clip space warped by N_T
//     ([Hempe 2004, §4.1.2]), the trapezoid built around the focus body, the camera frustum ∩ the
//     scene (focus_body.h).
// Against self-shadowing ([Hempe 2004, §3.2]): polygon offset or back faces only in the map pass,
// or a constant bias in the comparison (shadow_lookup.h).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "gl/depth_compare_sampler.h"
#include "gl/pipeline.h"
#include "gl/raster_stats.h"
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
  glm::dvec3 depthAnchor{0.0};           // with trapezoidal: where the view axis enters the body
  glm::dmat4 warp{1.0};                  // with trapezoidal: focusedDepthWarp(N_T, ...), or N_T when affine
  bool focusedDepth = false;             // warp is focusedDepthWarp (map pass with depth clamp)
  bool fittedToCasters = false;          // directional, standard: the map of caster_fit.h
  std::vector<size_t> fittedCasters;     // with fittedToCasters: the casters it was fitted to

  LightShadow() = default;
  LightShadow(const LightShadow&) = delete;  // the lookups point into `textures`
  LightShadow& operator=(const LightShadow&) = delete;

  // 1 where lit, the compare-fail value where shadowed, between them at PCF edges. Behind a spot
  // light (w ≤ 0 in its unwarped clip space) 1, as ShadowLookup does for a standard map: N_T's q
  // can be positive there.
  // `receiverPlane`: the world plane of the point's triangle (trianglePlane), which PCF with
  // receiver-plane depth bias follows (ShadowLookup::receiverPlaneBias).
  double factor(const glm::dvec3& worldPosition, const glm::dvec4& receiverPlane = glm::dvec4(0.0)) const;
  // factor() of `count` points on one receiver plane given as coordinate columns, into out[k]
  // (ShadowLookup::factors).
  void factors(const double* x, const double* y, const double* z, int count, double* out,
               const glm::dvec4& receiverPlane = glm::dvec4(0.0)) const;
  int mapCount() const { return cube ? 6 : 1; }
};

// The world plane (trianglePlane) of the triangle a fragment was interpolated from, from its
// vertices' world positions (the varyings at kVaryingPosition, gl/lighting.h); no plane when the
// fragment has no triangle (FragmentInput::triangle).
glm::dvec4 receiverPlaneOf(const ClipVertex* const triangle[3]);

// The world box the maps are fitted to: every instance's bounds.
Aabb sceneBounds(const std::vector<Instance>& instances);

// The warp the TSM map is drawn and looked up with: N_T (x, y, w rows as [Hempe 2004, §4.1.2]) with
// its depth row replaced, so the warped depth of a point at light depth Z (NDC) on a ray whose
// warped w is w'' times the light's becomes s · (Z − Z0) / w'' instead of Z / w'':
//   - N_T keeps z and divides it by w'' (1 at the top line, up to (η + λ)/η at the base), which
//     adds a depth gradient Z · ∇(1/w'') across the map that no surface has; polygon offset's
//     slope term follows it. For a spot light, whose depths Z all lie near 1, it can exceed the
//     depth distance between an occluder and its receiver, and then no shadow survives the offset.
//     With Z0 the false gradient is s · (Z − Z0) · ∇(1/w''): zero at depth Z0. ∇(1/w'') is largest
//     where w'' is small, at the top line, near the camera; so Z0 = the light depth of `anchor`,
//     the point where the view axis enters the focus body (clamped to the body's depth range);
//   - s = 1 / the larger distance from Z0 to the ends of the body's depth range (plus
//     kFocusedDepthMargin) spends the depth buffer on the visible part: receivers in the body
//     get |depth| ≤ 1; casters nearer the light fall below −1 and are clamped to window depth 0
//     (depth clamp in the map pass), still in front of everything they shadow.
// Order along each light ray is kept (s > 0, w'' > 0 there), and the depth stays affine in the
// warped map's window space, so the rasterizer interpolates it exactly. An empty body: the
// range [−1, 1].
inline constexpr double kFocusedDepthMargin = 1e-3;
inline constexpr double kMinFocusedDepthHalfRange = 1e-6;
glm::dmat4 focusedDepthWarp(const glm::dmat4& NT, const LightView& light, const std::vector<glm::dvec3>& body,
                            const glm::dvec3& anchor);

// The polygon offset factor the map pass uses for a k × k PCF lookup without receiver-plane
// depth bias (with it, `offsetFactor` unchanged: each tap compares the receiver's own plane
// there, ShadowLookup::receiverPlaneBias): `offsetFactor` × the
// kernel's width w (w = 2 · ⌊k/2⌋ + 1, the taps samplePcf reads). Why: a receiver is its own
// caster in the map, a plane of depth slopes g_x, g_y per texel. The nearest tap's centre lies at
// most half a texel from the point in each axis, the outer taps ⌊k/2⌋ texels further, so the
// plane's depth there is at most (|g_x| + |g_y|) · w/2 ≤ m · w nearer the light than the point,
// m = max(|g_x|, |g_y|), the slope term of glPolygonOffset ([GL 2.1, §3.5.5]). The factor that
// keeps nearest sampling (w = 1) free of acne, 1.1 by default, keeps every tap of the kernel free
// of it when multiplied by w; a fixed offset leaves the outer taps of a sloped receiver shadowing
// it (the moiré of [Isidoro 2006], who tilts the comparison by the receiver's plane instead).
// The cost: w times the offset also lifts shadows w times as far off their casters' feet
// (peter-panning). The units term covers rounding, not the slope, and is left alone; so is a
// constant bias.
inline int pcfKernelWidth(int pcf) { return pcf > 1 ? 2 * (pcf / 2) + 1 : 1; }
double pcfOffsetFactor(double offsetFactor, int pcf, ReceiverPlaneBias receiverPlaneBias);

// The light view of a standard (untrapezoidal) map of a directional or spot light: with
// `shadow.fit: casters` a directional light's map is fitted to the casters that can shadow what
// the camera sees (caster_fit.h), otherwise to `bounds`. The benchmark's GL side draws its map
// through the same view, so both draw the same map.
struct StandardMapView {
  LightView view;
  bool fittedToCasters = false;  // a visible point outside the map is shadowed by nothing
  std::vector<size_t> casters;   // with fittedToCasters: the casters it was fitted to
};
StandardMapView standardMapView(const Scene& scene, const std::vector<Instance>& instances, const SceneView& view,
                                const Light& light, const Aabb& bounds);

// Renders `light`'s map(s) with the scene's ShadowSettings and sets up the lookup. `trapezoidal`
// selects TSM for directional and spot lights (point lights always get cube maps). Each map is
// drawn by a pipeline like `frame` (Pipeline::forFramebuffer). Raster work adds to `stats`.
std::unique_ptr<LightShadow> buildLightShadow(const Scene& scene, const std::vector<Instance>& instances,
                                              const SceneView& view, const Light& light, bool trapezoidal,
                                              const Pipeline& frame, RasterStats& stats);

// Step 1 alone: depth from the light into a size × size map through `view` and `projection`
// (P_light, or N_T · P_light for TSM, [Hempe 2004, Listing 11]). Casters are the instances' shadow
// meshes (the low-poly proxy where given, [DSS article]) within the light's range. clipNear > 0:
// triangles are first clipped to the front of the light's near plane at that distance (a
// perspective map warped by N_T, see light_shadow.cpp). depthClamp: ARB_depth_clamp in the
// pass (TSM). Drawn by a pipeline like `frame` (Pipeline::forFramebuffer), in one pass.
DepthTexture renderDepthMap(const Scene& scene, const std::vector<Instance>& instances, const Light& light,
                            const glm::dmat4& view, const glm::dmat4& projection, const Pipeline& frame,
                            RasterStats& stats, double clipNear = 0.0, bool depthClamp = false);

}  // namespace shadowref
