#include "support/polygon_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadowref::testing {

bool pointInPolygon(const Polygon2& polygon, const glm::dvec2& p) {
  bool inside = false;
  const size_t n = polygon.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    const glm::dvec2& a = polygon[i];
    const glm::dvec2& b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y)) {
      const double xCross = a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
      if (p.x < xCross) inside = !inside;
    }
  }
  return inside;
}

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

double distanceToOutline(const Polygon2& polygon, const glm::dvec2& p) {
  double d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < polygon.size(); ++i)
    d = std::min(d, distanceToSegment(p, polygon[i], polygon[(i + 1) % polygon.size()]));
  return d;
}

int expectedCoverage(const Polygon2& polygon, const glm::dvec2& centre, double margin) {
  if (distanceToOutline(polygon, centre) < margin) return -1;
  return pointInPolygon(polygon, centre) ? 1 : 0;
}

}  // namespace shadowref::testing
