#include "shadow/focused_trapezoid.h"

#include <algorithm>

namespace shadowref {

namespace {

glm::dvec2 projectXY(const glm::dvec4& clip) { return glm::dvec2(clip) / clip.w; }

bool allInFront(const std::array<glm::dvec4, 8>& clip) {
  return std::all_of(clip.begin(), clip.end(), [](const glm::dvec4& c) { return c.w > 0.0; });
}

}  // namespace

Trapezoid focusedTrapezoid(const std::array<glm::dvec4, 8>& frustumClip, const glm::dvec4& axisNearClip,
                           const glm::dvec4& axisFarClip, const std::vector<glm::dvec4>& bodyClip,
                           double focusRegion) {
  if (bodyClip.empty()) return computeTrapezoid(frustumClip, focusRegion);

  // 1. The body's points in light post-projective x-y.
  std::vector<glm::dvec2> p;
  p.reserve(bodyClip.size());
  for (const glm::dvec4& c : bodyClip) p.push_back(projectXY(c));

  // A view axis reaching behind a spot light has no image to build on.
  if (!(axisNearClip.w > 0.0) || !(axisFarClip.w > 0.0)) return boundingRectangle(p);
  // The degenerate case is the frustum's, as in computeTrapezoid. A frustum reaching behind a
  // spot light (a light inside the scene, seen by a camera below it: the room) has no image of
  // its far polygon; its body, clipped to the light's volume, still has a trapezoid.
  bool degenerate = false;
  if (allInFront(frustumClip)) {
    std::array<glm::dvec2, 8> corners;
    for (size_t i = 0; i < 8; ++i) corners[i] = projectXY(frustumClip[i]);
    degenerate = nearPlaneInsideFarPlane(corners);
  }
  // 2. The centre line: the view axis.
  const glm::dvec2 nearCentre = projectXY(axisNearClip), farCentre = projectXY(axisFarClip);
  if (auto fallback = centreLineFallback(p, nearCentre, farCentre, degenerate)) return *fallback;

  Trapezoid tz;
  tz.nearCentre = nearCentre;
  tz.farCentre = farCentre;
  const glm::dvec2 d = glm::normalize(farCentre - nearCentre);
  const glm::dvec2 n(-d.y, d.x);

  // 3. Top line through the body's nearest, base line through its farthest point.
  double sMin = kInfinity, sMax = -kInfinity;
  for (const glm::dvec2& q : p) {
    sMin = std::min(sMin, glm::dot(q - nearCentre, d));
    sMax = std::max(sMax, glm::dot(q - nearCentre, d));
  }
  tz.lambda = sMax - sMin;
  if (!(tz.lambda > 0.0)) return boundingRectangle(p);  // a body flat across the view axis

  // 4. The 80 % rule ([Hempe 2004, §4.1.2]).
  tz.focusPoint = projectXY(axisNearClip + (axisFarClip - axisNearClip) * focusRegion);
  tz.deltaPrime = glm::dot(tz.focusPoint - nearCentre, d) - sMin;
  const double denominator = tz.lambda - 2.0 * tz.deltaPrime - tz.lambda * kEightyPercentLine;

  // 5. Side lines through the outermost points, 6. N_T — as in computeTrapezoid; a body without
  // width falls back to the bounding rectangle.
  if (!(denominator > 0.0)) {
    if (!fitParallelSides(tz, p, nearCentre, d, n, sMin, sMax)) return boundingRectangle(p);
    return tz;
  }
  // A body seen edge-on from q (all points on one line) has no trapezoid.
  if (!fitSideLinesFromApex(tz, p, nearCentre, d, n, sMin)) return boundingRectangle(p);
  return tz;
}

}  // namespace shadowref
