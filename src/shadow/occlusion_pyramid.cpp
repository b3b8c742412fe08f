#include "shadow/occlusion_pyramid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace shadowref {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A convex set given as the hull of finitely many points, optionally swept to infinity along a
// direction (the directional light's prism).
struct ConvexHull {
  std::array<glm::dvec3, 5> points;
  int pointCount = 0;
  bool hasRay = false;
  glm::dvec3 ray{0.0};
};

struct Interval {
  double lo, hi;
};

Interval project(const ConvexHull& hull, const glm::dvec3& axis) {
  Interval r{kInf, -kInf};
  for (int i = 0; i < hull.pointCount; ++i) {
    const double d = glm::dot(axis, hull.points[i]);
    r.lo = std::min(r.lo, d);
    r.hi = std::max(r.hi, d);
  }
  if (hull.hasRay) {
    const double s = glm::dot(axis, hull.ray);
    if (s > 0.0) r.hi = kInf;
    if (s < 0.0) r.lo = -kInf;
  }
  return r;
}

Interval project(const Aabb& box, const glm::dvec3& axis) {
  const glm::dvec3 c = box.center(), h = (box.max - box.min) * 0.5;
  const double mid = glm::dot(axis, c);
  const double radius = std::abs(axis.x) * h.x + std::abs(axis.y) * h.y + std::abs(axis.z) * h.z;
  return {mid - radius, mid + radius};
}

// Separated along `axis` by more than `tolerance` (touching is not separated).
bool separates(const ConvexHull& hull, const Aabb& box, glm::dvec3 axis, double tolerance) {
  const double len = glm::length(axis);
  if (!(len > 1e-12)) return false;  // degenerate axis: cannot prove anything
  axis /= len;
  const Interval a = project(hull, axis), b = project(box, axis);
  return b.hi < a.lo - tolerance || b.lo > a.hi + tolerance;
}

ConvexHull hullOf(const OcclusionPyramid& p) {
  ConvexHull h;
  for (const glm::dvec3& c : p.nearCorners) h.points[h.pointCount++] = c;
  if (p.light.w != 0.0) {
    h.points[h.pointCount++] = glm::dvec3(p.light) / p.light.w;
  } else {
    h.hasRay = true;
    h.ray = glm::dvec3(p.light);
  }
  return h;
}

}  // namespace

std::array<glm::dvec3, 4> nearPlaneCorners(const Camera& camera, double aspect) {
  const glm::dvec3 forward = glm::normalize(camera.target - camera.eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::dvec3 up = glm::cross(right, forward);
  const glm::dvec3 centre = camera.eye + forward * camera.nearPlane;
  const double halfHeight = std::tan(camera.fovYDegrees * std::numbers::pi / 360.0) * camera.nearPlane;
  const double halfWidth = halfHeight * aspect;  // not tan(fovX/2)·near with the fovX of [Kuhn 2016, §4.2.1]: see header
  const glm::dvec3 w = right * halfWidth, h = up * halfHeight;
  return {centre - w - h, centre + w - h, centre + w + h, centre - w + h};
}

OcclusionPyramid makeOcclusionPyramid(const Camera& camera, double aspect, const glm::dvec4& worldLight) {
  return OcclusionPyramid{nearPlaneCorners(camera, aspect), worldLight};
}

bool intersects(const OcclusionPyramid& pyramid, const Aabb& box) {
  if (box.empty()) return false;
  const ConvexHull hull = hullOf(pyramid);
  const auto& c = pyramid.nearCorners;

  // Edges of the hull: the rectangle's four sides and the four lateral edges (or the ray).
  std::array<glm::dvec3, 8> edges;
  int edgeCount = 0;
  for (int i = 0; i < 4; ++i) edges[edgeCount++] = c[(i + 1) % 4] - c[i];
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 lateral = hull.hasRay ? hull.ray : hull.points[4] - c[i];
    edges[edgeCount++] = lateral;
    if (hull.hasRay) break;  // all four rays are parallel
  }

  // Tolerance scaled to the coordinates involved, leaning towards "meets".
  double scale = glm::length(box.max - box.min) + glm::length(box.center());
  for (int i = 0; i < hull.pointCount; ++i) scale = std::max(scale, glm::length(hull.points[i]));
  const double tolerance = 1e-9 * scale;

  std::array<glm::dvec3, 3 + 5 + 3 * 8> axes;
  int axisCount = 0;
  for (int k = 0; k < 3; ++k) {  // the box's face normals
    axes[axisCount] = glm::dvec3(0.0);
    axes[axisCount++][k] = 1.0;
  }
  axes[axisCount++] = glm::cross(c[1] - c[0], c[3] - c[0]);  // the rectangle's plane
  for (int i = 0; i < 4; ++i) {                              // the side faces
    const glm::dvec3 lateral = hull.hasRay ? hull.ray : hull.points[4] - c[i];
    axes[axisCount++] = glm::cross(c[(i + 1) % 4] - c[i], lateral);
  }
  for (int k = 0; k < 3; ++k)  // box edge x hull edge
    for (int e = 0; e < edgeCount; ++e) axes[axisCount++] = glm::cross(axes[k], edges[e]);

  for (int i = 0; i < axisCount; ++i)
    if (separates(hull, box, axes[i], tolerance)) return false;
  return true;
}

bool needsZFail(const Aabb& worldBox, const Camera& camera, double aspect, const glm::dvec4& worldLight) {
  return intersects(makeOcclusionPyramid(camera, aspect, worldLight), worldBox);
}

}  // namespace shadowref
