#include "shadow/trapezoid.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace shadowref {

namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b) { return a.x * b.y - a.y * b.x; }

glm::dvec2 projectXY(const glm::dvec4& clip) { return glm::dvec2(clip) / clip.w; }

glm::dvec4 meanOf(const std::array<glm::dvec4, 8>& c, size_t first) {
  return (c[first] + c[first + 1] + c[first + 2] + c[first + 3]) / 4.0;
}

}  // namespace

std::array<glm::dvec3, 8> frustumCorners(const Camera& camera, double aspect, double farOverride) {
  const double farPlane = farOverride > 0.0 ? farOverride : camera.farPlane;
  // The camera basis of gluLookAt (projection.h), so the corners match perspective() exactly.
  const glm::dvec3 f = glm::normalize(camera.target - camera.eye);
  const glm::dvec3 s = glm::normalize(glm::cross(f, camera.up));
  const glm::dvec3 u = glm::cross(s, f);
  const double tanHalf = std::tan(camera.fovYDegrees * std::numbers::pi / 360.0);
  std::array<glm::dvec3, 8> c;
  const double depths[2] = {camera.nearPlane, farPlane};
  for (size_t plane = 0; plane < 2; ++plane) {
    const double d = depths[plane];
    const double h = d * tanHalf, w = h * aspect;
    const glm::dvec3 centre = camera.eye + f * d;
    c[plane * 4 + 0] = centre - s * w - u * h;
    c[plane * 4 + 1] = centre + s * w - u * h;
    c[plane * 4 + 2] = centre + s * w + u * h;
    c[plane * 4 + 3] = centre - s * w + u * h;
  }
  return c;
}

double fitFarToBounds(const Camera& camera, const Aabb& bounds) {
  const glm::dvec3 f = glm::normalize(camera.target - camera.eye);
  double farthest = -kInfinity;
  for (int i = 0; i < 8; ++i) {
    const glm::dvec3 c{(i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                       (i & 4) ? bounds.max.z : bounds.min.z};
    farthest = std::max(farthest, glm::dot(c - camera.eye, f));
  }
  return std::clamp(farthest, 2.0 * camera.nearPlane, std::max(camera.farPlane, 2.0 * camera.nearPlane));
}

std::array<glm::dvec4, 8> transformCorners(const glm::dmat4& m, const std::array<glm::dvec3, 8>& corners) {
  std::array<glm::dvec4, 8> out;
  for (size_t i = 0; i < 8; ++i) out[i] = m * glm::dvec4(corners[i], 1.0);
  return out;
}

double trapezoidEta(double lambda, double deltaPrime, double xi) {
  return (lambda * deltaPrime + lambda * deltaPrime * xi) / (lambda - 2.0 * deltaPrime - lambda * xi);
}

bool nearPlaneInsideFarPlane(const std::array<glm::dvec2, 8>& p) {
  double area = 0.0;
  for (size_t j = 0; j < 4; ++j) area += cross2(p[4 + j], p[4 + (j + 1) % 4]);
  if (area == 0.0) return false;
  const double orientation = area > 0.0 ? 1.0 : -1.0;
  for (size_t k = 0; k < 4; ++k)
    for (size_t j = 0; j < 4; ++j) {
      const glm::dvec2 a = p[4 + j], b = p[4 + (j + 1) % 4];
      if (!(orientation * cross2(b - a, p[k] - a) > 0.0)) return false;
    }
  return true;
}

Trapezoid boundingRectangle(std::span<const glm::dvec2> points) {
  glm::dvec2 lo(kInfinity), hi(-kInfinity);
  for (const glm::dvec2& q : points) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  lo = glm::max(lo, glm::dvec2(-1.0));
  hi = glm::min(hi, glm::dvec2(1.0));
  if (!(lo.x < hi.x && lo.y < hi.y)) lo = glm::dvec2(-1.0), hi = glm::dvec2(1.0);
  Trapezoid tz;
  tz.fallback = true;
  tz.t[0] = {lo.x, lo.y};
  tz.t[1] = {hi.x, lo.y};
  tz.t[2] = {hi.x, hi.y};
  tz.t[3] = {lo.x, hi.y};
  tz.NT = parallelogramToSquare({tz.t[0], tz.t[1], tz.t[2], tz.t[3]});
  return tz;
}

std::optional<Trapezoid> centreLineFallback(std::span<const glm::dvec2> points, const glm::dvec2& nearCentre,
                                            const glm::dvec2& farCentre, bool degenerate) {
  double extent = 0.0;
  for (const glm::dvec2& q : points) extent = std::max(extent, glm::length(q - nearCentre));
  if (!degenerate && glm::length(farCentre - nearCentre) > 1e-12 * extent) return std::nullopt;
  Trapezoid tz = boundingRectangle(points);
  tz.nearCentre = nearCentre;
  tz.farCentre = farCentre;
  return tz;
}

Trapezoid computeTrapezoid(const std::array<glm::dvec4, 8>& clip, double focusRegion) {
  for (const glm::dvec4& c : clip)
    if (!(c.w > 0.0)) {
      Trapezoid standard;  // no trapezoid behind the light: standard mapping, N_T = identity
      standard.fallback = true;
      standard.t[0] = {-1.0, -1.0}, standard.t[1] = {1.0, -1.0};
      standard.t[2] = {1.0, 1.0}, standard.t[3] = {-1.0, 1.0};
      return standard;
    }

  // 1. ([Hempe 2004, §4.1.2 step 1]) the corners in light post-projective x-y.
  std::array<glm::dvec2, 8> p;
  for (size_t i = 0; i < 8; ++i) p[i] = projectXY(clip[i]);
  // 2. The centre line. The plane centres are averaged before the division by w, so they are
  // the images of the true centres also under a perspective (spot) light.
  const glm::dvec4 nearClip = meanOf(clip, 0), farClip = meanOf(clip, 4);
  const glm::dvec2 nearCentre = projectXY(nearClip), farCentre = projectXY(farClip);

  if (auto fallback = centreLineFallback(p, nearCentre, farCentre, nearPlaneInsideFarPlane(p))) return *fallback;

  Trapezoid tz;
  tz.nearCentre = nearCentre;
  tz.farCentre = farCentre;
  const glm::dvec2 d = glm::normalize(farCentre - nearCentre);  // along the centre line
  const glm::dvec2 n(-d.y, d.x);                                 // the "Mittellinienorthogonale"

  // 3. Top line through the nearest, base line through the farthest corner.
  double sMin = kInfinity, sMax = -kInfinity;
  for (const glm::dvec2& q : p) {
    sMin = std::min(sMin, glm::dot(q - nearCentre, d));
    sMax = std::max(sMax, glm::dot(q - nearCentre, d));
  }
  tz.lambda = sMax - sMin;

  // 4. The 80 % rule: the focus point on the view axis, δ' beyond the top line, and η.
  tz.focusPoint = projectXY(nearClip + (farClip - nearClip) * focusRegion);
  tz.deltaPrime = glm::dot(tz.focusPoint - nearCentre, d) - sMin;
  const double denominator = tz.lambda - 2.0 * tz.deltaPrime - tz.lambda * kEightyPercentLine;

  // 5. The side lines, through the outermost corners as seen from q; 6. N_T.
  if (!(denominator > 0.0)) fitParallelSides(tz, p, nearCentre, d, n, sMin, sMax);  // η = ∞
  else fitSideLinesFromApex(tz, p, nearCentre, d, n, sMin);
  return tz;
}

bool fitParallelSides(Trapezoid& tz, std::span<const glm::dvec2> points, const glm::dvec2& nearCentre,
                      const glm::dvec2& d, const glm::dvec2& n, double sMin, double sMax) {
  // q at infinity: side lines parallel to the centre line.
  double bMin = kInfinity, bMax = -kInfinity;
  for (const glm::dvec2& q : points) {
    bMin = std::min(bMin, glm::dot(q - nearCentre, n));
    bMax = std::max(bMax, glm::dot(q - nearCentre, n));
  }
  tz.parallelSides = true;
  tz.eta = kInfinity;
  tz.t[0] = nearCentre + sMax * d + bMin * n;
  tz.t[1] = nearCentre + sMax * d + bMax * n;
  tz.t[2] = nearCentre + sMin * d + bMax * n;
  tz.t[3] = nearCentre + sMin * d + bMin * n;
  tz.NT = parallelogramToSquare({tz.t[0], tz.t[1], tz.t[2], tz.t[3]});
  return bMax > bMin;
}

bool fitSideLinesFromApex(Trapezoid& tz, std::span<const glm::dvec2> points, const glm::dvec2& nearCentre,
                          const glm::dvec2& d, const glm::dvec2& n, double sMin) {
  // δ' = 0 (focusRegion 0 with the near centre on the top line) would put q on the top line and
  // collapse t2, t3; keep q a hair behind it.
  tz.eta = std::max(trapezoidEta(tz.lambda, tz.deltaPrime), 1e-9 * tz.lambda);
  tz.apex = nearCentre + (sMin - tz.eta) * d;

  // Slopes b/a of each point seen from q, in the (d, n) frame: every point has a >= η > 0.
  double leftSlope = -kInfinity, rightSlope = kInfinity;
  for (const glm::dvec2& q : points) {
    const glm::dvec2 v = q - tz.apex;
    const double slope = glm::dot(v, n) / glm::dot(v, d);
    leftSlope = std::max(leftSlope, slope);
    rightSlope = std::min(rightSlope, slope);
  }
  const double aTop = tz.eta, aBase = tz.eta + tz.lambda;
  tz.t[0] = tz.apex + aBase * d + rightSlope * aBase * n;  // base, right of the centre line
  tz.t[1] = tz.apex + aBase * d + leftSlope * aBase * n;   // base, left
  tz.t[2] = tz.apex + aTop * d + leftSlope * aTop * n;     // top, left
  tz.t[3] = tz.apex + aTop * d + rightSlope * aTop * n;    // top, right

  // 6. N_T ([Hempe 2004, §4.1.2], 8 steps).
  tz.NT = trapezoidToSquare({tz.t[0], tz.t[1], tz.t[2], tz.t[3]});
  return leftSlope > rightSlope;
}

TrapezoidalView trapezoidalView(const Camera& camera, double aspect, const LightView& light,
                                const Aabb& sceneBounds, double focusRegion) {
  TrapezoidalView v;
  v.light = light;
  const auto corners = frustumCorners(camera, aspect, fitFarToBounds(camera, sceneBounds));
  v.trapezoid = computeTrapezoid(transformCorners(light.projection * light.view, corners), focusRegion);
  v.mapProjection = v.trapezoid.NT * light.projection;
  v.texture = textureMatrix(light, v.trapezoid.NT);
  return v;
}

}  // namespace shadowref
