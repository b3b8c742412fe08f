#include "oracle/edge_marks.h"

#include <algorithm>
#include <cmath>

namespace shadowref::oracle {

namespace {

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double s = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + s * ab));
}

}  // namespace

void markNearSegment(const CameraModel& camera, glm::dvec4 a, glm::dvec4 b, double radius, std::vector<uint8_t>& marks) {
  glm::dvec4 ca = camera.toClip(a), cb = camera.toClip(b);
  if (!clipSegmentToView(ca, cb)) return;
  const Viewport& vp = camera.viewport;
  const glm::dvec2 wa = camera.toWindow(ca) - glm::dvec2(vp.x, vp.y);
  const glm::dvec2 wb = camera.toWindow(cb) - glm::dvec2(vp.x, vp.y);
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min(wa.x, wb.x) - radius - 0.5)));
  const int x1 = std::min(vp.width - 1, static_cast<int>(std::ceil(std::max(wa.x, wb.x) + radius)));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min(wa.y, wb.y) - radius - 0.5)));
  const int y1 = std::min(vp.height - 1, static_cast<int>(std::ceil(std::max(wa.y, wb.y) + radius)));
  const glm::dvec2 dir = wb - wa;
  const double len = glm::length(dir);
  for (int y = y0; y <= y1; ++y) {
    // Only the columns near the segment in this row, so a long diagonal edge costs its length.
    int cx0 = x0, cx1 = x1;
    if (len > 0.0 && std::abs(dir.y) > 1e-9 * len) {
      const double yc = y + 0.5;
      const double s0 = std::clamp((yc - radius - wa.y) / dir.y, 0.0, 1.0);
      const double s1 = std::clamp((yc + radius - wa.y) / dir.y, 0.0, 1.0);
      const double xa = wa.x + dir.x * s0, xb = wa.x + dir.x * s1;
      // The nearest segment point of a centre within `radius` lies in this band of rows, so the
      // centre's x is within `radius` of the band's x range.
      cx0 = std::max(x0, static_cast<int>(std::floor(std::min(xa, xb) - radius - 0.5)));
      cx1 = std::min(x1, static_cast<int>(std::ceil(std::max(xa, xb) + radius)));
    }
    for (int x = cx0; x <= cx1; ++x) {
      if (distanceToSegment({x + 0.5, y + 0.5}, wa, wb) <= radius) marks[static_cast<size_t>(y) * vp.width + x] = 1;
    }
  }
}

}  // namespace shadowref::oracle
