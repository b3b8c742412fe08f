// The trapezoid of [Hempe 2004, §4.1.2] built around the focus body (focus_body.h) instead of the
// eight frustum corners: the same construction as computeTrapezoid (trapezoid.h), with its errata,
// applied to a point set —
//  - the centre line is still the camera's view axis in light space (through the images of the
//    near- and far-plane centres), so the trapezoid opens towards the camera as [Hempe 2004] wants;
//  - top and base lines through the body's nearest and farthest points along it; λ their distance;
//  - the focus point lies on the view axis at the fraction focusRegion of the body's depth range
//    along the view direction (with the far plane fitted to the scene, trapezoid.h measures it
//    over near … fitted far; here over the body, whose depth range is that one clipped to the
//    scene) and η follows from the 80 % rule;
//  - the side lines from q through the body's outermost points.
// The degenerate case is decided on the whole frustum exactly as computeTrapezoid does (near
// polygon inside the far polygon: the camera looks along the light); it falls back to the
// bounding rectangle of the body. A frustum reaching behind a spot light (a light inside the
// scene) has no far polygon to test; its body, clipped to the light's volume, is used as it is.
// With the body equal to the frustum this is computeTrapezoid.
#pragma once

#include <array>
#include <vector>

#include <glm/glm.hpp>

#include "shadow/trapezoid.h"

namespace shadowref {

// frustumClip: the eight frustum corners in light clip space (every w > 0); axisNearClip and
// axisFarClip: two points of the view axis in light clip space, the near one first (the ends of
// the body's depth range along the view direction); body: the body's vertices in light clip
// space (every w > 0). An empty body gives computeTrapezoid(frustumClip, focusRegion).
Trapezoid focusedTrapezoid(const std::array<glm::dvec4, 8>& frustumClip, const glm::dvec4& axisNearClip,
                           const glm::dvec4& axisFarClip, const std::vector<glm::dvec4>& bodyClip,
                           double focusRegion);

}  // namespace shadowref
