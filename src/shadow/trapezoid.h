// Trapezoidal shadow maps ([Hempe 2004, §4.1, §5.2]; [Martin & Tan 2004],
// "Anti-aliasing and Continuity with Trapezoidal Shadow Maps"): the trapezoid around the camera
// frustum as the light sees it, and the matrix N_T that warps it onto the shadow map's square.
//
// Works in the light's post-projective space (after P_light · V_light and the division by w),
// 2D x-y, as Listing 10e's final division by the ortho extent does. The construction, with the
// names of [Hempe 2004, §4.1.2]:
//  1. the eight frustum corners p0…p7 in that space (near 0–3, far 4–7, see frustumCorners);
//  2. the centre line ("Mittellinie") through the centres of the near and far planes;
//  3. the top line through the corner nearest along the centre line, the base line orthogonal to
//     the centre line through the farthest; λ = their distance;
//  4. the 80 % rule: the focus point p, at the fraction δ = focusRegion of the way from the near
//     to the far plane along the view direction, lies δ' beyond the top line; the apex q lies η
//     beyond the top line, away from the base, with η = (λδ' + λδ'ξ) / (λ − 2δ' − λξ), ξ = −0.6,
//     so that N_T maps p to y = ξ;
//  5. the side lines from q through the outermost corners (largest angle to the centre line on
//     each side), and t0…t3 where they meet the base (t0, t1) and top (t2, t3) lines;
//  6. N_T from trapezoid_to_square.h.
//
// Where [Hempe 2004] is wrong or ambiguous, and what this code does:
//  - §4.1.2 step 3 calls the line nearest the camera the "Base Line" and the farthest the "Top
//    Line"; its own 80 % rule (η measured from the top line, towards the camera) and the N_T steps
//    (T1 centres the top line t2–t3, the short side) use Martin & Tan's naming, top = near. Here:
//    top = near, base = far, throughout.
//  - Listing 10c fixes λ = 1, δ' = focusRegion · λ and ξ = −(1 − focusRegion), so "0.4" is both
//    the focus depth and the 80 % line. Here ξ = −0.6 is the 80 % line (§4.1.2 text, Martin &
//    Tan) and δ' is measured to an actual focus point, so the rule can be checked: p maps to −0.6.
//    focusRegion is a fraction of the frustum depth (far − near) from the near plane; the thesis
//    says "distance δ from the camera origin", which differs by the (small) near distance.
//  - §4.1.2 step 4 and Listing 10d draw the side lines through the far-plane corners only; a
//    near corner can stick out past them when the light comes from the side. Here all eight
//    corners decide (Martin & Tan: the hull of the frustum), so the trapezoid always encloses it.
//  - Listing 10d orders t0/t1 by camera-space x with an extra test for an upside-down camera.
//    Here t0…t3 are ordered counter-clockwise in light space (t0 base-right, t1 base-left,
//    t2 top-left, t3 top-right, seen with the base up), which makes N_T orientation-preserving.
//  - The degenerate case (Listing 10e): the thesis' code falls back when ANY near corner lies
//    inside the far-plane polygon; its text says first "one of", then "all four" near corners.
//    Here: all four, i.e. the near polygon
//    inside the far polygon. For an orthographic light that happens exactly when the
//    light direction (or its opposite) lies strictly inside the camera's field of view:
//    |L_x / L_z| < tan(fovX/2) and |L_y / L_z| < tan(fovY/2) in camera space, whatever near and
//    far. So it triggers for a cone of directions around "looking along the light", not only at
//    exact alignment: inside that cone the top line runs through a far corner behind the eye, and
//    the wedge from q must open wide to hold the whole far polygon, wasting most of the map.
//    The fallback is the bounding rectangle of all eight corners (clipped to the light's view
//    [−1, 1]²), not the far-plane polygon of Listing 10e, which the thesis itself notes can miss
//    parts of the frustum ("Bereiche ..., für die keine korrekte Shadow Map entsteht").
//  - When λ − 2δ' − λξ ≤ 0 (focus point beyond the 80 % line already, η infinite) the side lines
//    are parallel: the trapezoid's limit is the rectangle along the centre line (parallelSides).
#pragma once

#include <array>
#include <optional>
#include <span>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "shadow/light_view.h"
#include "shadow/trapezoid_to_square.h"

namespace shadowref {

// ξ: the 80 % line of [Hempe 2004, §4.1.2] — the focus point lands at y = −0.6, so 80 % of the
// map's height, from y = +1 (top line) down to −0.6, is spent on the focus region.
inline constexpr double kEightyPercentLine = -0.6;

struct Trapezoid {
  glm::dvec2 t[4]{};      // t0, t1 base line; t2, t3 top line; counter-clockwise
  glm::dvec2 apex{0.0};   // q (meaningless when fallback or parallelSides)
  bool fallback = false;  // degenerate case: bounding rectangle of the frustum ([Hempe 2004, Listing 10e])
  bool parallelSides = false;  // η infinite: rectangle along the centre line
  glm::dmat4 NT{1.0};     // maps t0, t1, t2, t3 to (−1,−1), (1,−1), (1,1), (−1,1)

  // The construction, for tests and teaching dumps (light post-projective x-y).
  glm::dvec2 nearCentre{0.0}, farCentre{0.0};
  glm::dvec2 focusPoint{0.0};  // p (and p_l: it lies on the centre line)
  double lambda = 0.0, deltaPrime = 0.0, eta = 0.0;
};

// The world-space corners of the camera's view frustum, near plane first, each plane in the order
// (left, bottom), (right, bottom), (right, top), (left, top) as the camera sees them. The far
// plane is `farOverride` when > 0, else Camera::farPlane, which must then be finite (P_inf has no
// far plane: pass the distance from fitFarToBounds).
std::array<glm::dvec3, 8> frustumCorners(const Camera& camera, double aspect, double farOverride = 0.0);

// A finite far plane for TSM when the camera's is infinite or beyond the scene: the distance
// along the view direction to the farthest corner of `bounds`, at most Camera::farPlane, at
// least a little beyond the near plane.
double fitFarToBounds(const Camera& camera, const Aabb& bounds);

// clip = M · (corner, 1) for each corner; with M = P_light · V_light the input of computeTrapezoid.
std::array<glm::dvec4, 8> transformCorners(const glm::dmat4& m, const std::array<glm::dvec3, 8>& corners);

// The 1D perspective of [Hempe 2004, §4.1.2] solved for η, the distance of q from the top line:
// η = (λδ' + λδ'ξ) / (λ − 2δ' − λξ). Infinite (or negative) when λ − 2δ' − λξ ≤ 0.
double trapezoidEta(double lambda, double deltaPrime, double xi = kEightyPercentLine);

// The degenerate-case test of [Hempe 2004, Listing 10e]: all four near corners (p0…p3) strictly
// inside the far-plane polygon (p4…p7), in light post-projective x-y.
bool nearPlaneInsideFarPlane(const std::array<glm::dvec2, 8>& p);

// The trapezoid of [Hempe 2004, §4.1.2] for the frustum corners in light clip space (every w > 0:
// for a spot light the frustum must lie in front of the light; otherwise NT is the identity,
// fallback set). focusRegion in (0, 1); [Hempe 2004] uses 0.4.
Trapezoid computeTrapezoid(const std::array<glm::dvec4, 8>& frustumCornersLightClip, double focusRegion);

// The fallback of [Hempe 2004, Listing 10e]: the bounding rectangle of the points, clipped to the
// light's view [−1, 1]² (nothing outside it is in the map anyway; the whole view when nothing of it
// is left), as a trapezoid with `fallback` set. Shared by computeTrapezoid and focusedTrapezoid.
Trapezoid boundingRectangle(std::span<const glm::dvec2> points);

// Step 2's way out, shared by computeTrapezoid and focusedTrapezoid: for a degenerate frustum, or
// a centre line whose ends coincide up to rounding (shorter than 1e-12 of the points' extent
// around nearCentre), the bounding rectangle with the centres kept; otherwise nothing.
std::optional<Trapezoid> centreLineFallback(std::span<const glm::dvec2> points, const glm::dvec2& nearCentre,
                                            const glm::dvec2& farCentre, bool degenerate);

// Steps 5 and 6 of [Hempe 2004, §4.1.2], shared by computeTrapezoid and focusedTrapezoid. The
// frame: the centre line from `nearCentre` along the unit vector d, its unit normal n, the top line
// at s = sMin and the base line at s = sMax along d; tz.lambda and tz.deltaPrime are set.
// η = ∞: parallel side lines through the outermost points, N_T the parallelogram fit. Returns
// false when the points have no width across the centre line (the trapezoid is still filled).
bool fitParallelSides(Trapezoid& tz, std::span<const glm::dvec2> points, const glm::dvec2& nearCentre,
                      const glm::dvec2& d, const glm::dvec2& n, double sMin, double sMax);
// Finite η: the apex q at η behind the top line, the side lines from q through the outermost
// points, the corners t0…t3 and N_T. Returns false when every point lies on one line through q
// (no trapezoid; the corners are still filled).
bool fitSideLinesFromApex(Trapezoid& tz, std::span<const glm::dvec2> points, const glm::dvec2& nearCentre,
                          const glm::dvec2& d, const glm::dvec2& n, double sMin);

// One frame's trapezoidal shadow map, put together ([Hempe 2004, Listings 9, 11, 12]): the camera
// frustum, its far plane fitted to the scene (fitFarToBounds), in the light's clip space; the
// trapezoid; the map pass's projection N_T · P_light with view V_light (Listing 12 loads N_T as the
// projection and P_light · V_light as the modelview: the same product); the camera pass's texture
// matrix bias · N_T · P_light · V_light. Inside the trapezoid the warped w is ≥ 1 (it is y after step 5
// of N_T), so light depths |z| ≤ 1 are not clipped by the warp.
struct TrapezoidalView {
  LightView light;             // the unwarped light view (orthographic for [Hempe 2004])
  Trapezoid trapezoid;
  glm::dmat4 mapProjection{1.0};  // N_T · P_light: the projection of the map pass
  glm::dmat4 texture{1.0};        // bias · N_T · P_light · V_light
};
TrapezoidalView trapezoidalView(const Camera& camera, double aspect, const LightView& light,
                                const Aabb& sceneBounds, double focusRegion);

}  // namespace shadowref
