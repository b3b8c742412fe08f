#include "oracle/camera_model.h"

#include <array>
#include <cmath>
#include <limits>

namespace shadowref::oracle {

namespace {

// The five half-spaces f(X) >= 0 of clipPolygonToView.
constexpr int kPlaneCount = 5;
double planeDistance(int plane, const glm::dvec4& c) {
  switch (plane) {
    case 0: return c.z + c.w;                 // near
    case 1: return kGuardBand * c.w - c.x;
    case 2: return kGuardBand * c.w + c.x;
    case 3: return kGuardBand * c.w - c.y;
    default: return kGuardBand * c.w + c.y;
  }
}

}  // namespace

CameraModel makeCameraModel(const SceneView& view) {
  CameraModel m;
  m.viewProjection = view.projection * view.view;
  m.inverseViewProjection = glm::inverse(m.viewProjection);
  m.viewport = view.viewport;
  m.eye = view.eye;
  m.infinite = view.infinite;
  return m;
}

PixelRay CameraModel::rayThrough(double windowX, double windowY) const {
  const double ndcX = 2.0 * (windowX - viewport.x) / viewport.width - 1.0;
  const double ndcY = 2.0 * (windowY - viewport.y) / viewport.height - 1.0;
  const glm::dvec4 nearH = inverseViewProjection * glm::dvec4(ndcX, ndcY, -1.0, 1.0);
  PixelRay r;
  r.origin = eye;
  r.direction = glm::dvec3(nearH) / nearH.w - eye;
  r.tNear = 1.0;
  r.tFar = std::numeric_limits<double>::infinity();
  if (!infinite) {
    const glm::dvec4 farH = inverseViewProjection * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    const glm::dvec3 farPoint = glm::dvec3(farH) / farH.w;
    r.tFar = glm::dot(farPoint - eye, r.direction) / glm::dot(r.direction, r.direction);
  }
  return r;
}

glm::dvec2 CameraModel::toWindow(const glm::dvec4& clip) const {
  const double ndcX = clip.x / clip.w, ndcY = clip.y / clip.w;
  return {viewport.x + (ndcX + 1.0) * 0.5 * viewport.width, viewport.y + (ndcY + 1.0) * 0.5 * viewport.height};
}

std::vector<glm::dvec4> clipPolygonToView(std::vector<glm::dvec4> polygon) {
  std::vector<glm::dvec4> next;
  for (int plane = 0; plane < kPlaneCount && !polygon.empty(); ++plane) {
    next.clear();
    for (size_t i = 0; i < polygon.size(); ++i) {
      const glm::dvec4& a = polygon[i];
      const glm::dvec4& b = polygon[(i + 1) % polygon.size()];
      const double da = planeDistance(plane, a), db = planeDistance(plane, b);
      if (da >= 0.0) next.push_back(a);
      if ((da >= 0.0) != (db >= 0.0)) next.push_back(a + (b - a) * (da / (da - db)));
    }
    polygon.swap(next);
  }
  // A polygon that only touches a plane can keep points with w = 0 (the eye's plane); they do
  // not project, and no pixel ray beyond the near plane meets them.
  std::erase_if(polygon, [](const glm::dvec4& c) { return !(c.w > 0.0); });
  return polygon;
}

bool clipSegmentToView(glm::dvec4& a, glm::dvec4& b) {
  double t0 = 0.0, t1 = 1.0;
  for (int plane = 0; plane < kPlaneCount; ++plane) {
    const double da = planeDistance(plane, a), db = planeDistance(plane, b);
    if (da < 0.0 && db < 0.0) return false;
    if (da < 0.0) t0 = std::max(t0, da / (da - db));
    else if (db < 0.0) t1 = std::min(t1, da / (da - db));
  }
  if (t0 > t1) return false;
  const glm::dvec4 a0 = a, d = b - a;
  a = a0 + d * t0;
  b = a0 + d * t1;
  return a.w > 0.0 && b.w > 0.0;
}

}  // namespace shadowref::oracle
