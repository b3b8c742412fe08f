#include "conformance/edge_mask.h"

#include <algorithm>
#include <cmath>

namespace shadowref::conformance {

namespace {

using Polygon = std::vector<glm::dvec4>;

// Sutherland-Hodgman against one plane dot(plane, p) >= 0.
Polygon clipAgainst(const Polygon& in, const glm::dvec4& plane) {
  Polygon out;
  for (size_t i = 0; i < in.size(); ++i) {
    const glm::dvec4& a = in[i];
    const glm::dvec4& b = in[(i + 1) % in.size()];
    const double da = glm::dot(plane, a), db = glm::dot(plane, b);
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

// The clip volume, widened to |x|, |y| <= 4w so that window coordinates stay finite (edges out
// there lie outside the viewport and mark nothing), plus w > 0.
Polygon clipTriangle(const DrawStep& d, size_t first) {
  Polygon p = {d.vertices[first].clip, d.vertices[first + 1].clip, d.vertices[first + 2].clip};
  std::vector<glm::dvec4> planes = {{1, 0, 0, 4}, {-1, 0, 0, 4}, {0, 1, 0, 4}, {0, -1, 0, 4}, {0, 0, 0, 1}};
  if (!d.state.depthClamp) {
    planes.push_back({0, 0, 1, 1});   // near: z >= -w
    planes.push_back({0, 0, -1, 1});  // far: z <= w
  }
  for (const glm::dvec4& plane : planes) {
    if (p.size() < 3) break;
    p = clipAgainst(p, plane);
  }
  return p;
}

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

void markSegment(std::vector<bool>& mask, int width, int height, const glm::dvec2& a, const glm::dvec2& b,
                 double distance) {
  const int x0 = std::max(0, int(std::floor(std::min(a.x, b.x) - distance - 1)));
  const int x1 = std::min(width - 1, int(std::ceil(std::max(a.x, b.x) + distance + 1)));
  const int y0 = std::max(0, int(std::floor(std::min(a.y, b.y) - distance - 1)));
  const int y1 = std::min(height - 1, int(std::ceil(std::max(a.y, b.y) + distance + 1)));
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x)
      if (distanceToSegment({x + 0.5, y + 0.5}, a, b) <= distance) mask[size_t(y) * size_t(width) + size_t(x)] = true;
}

}  // namespace

std::vector<bool> edgeMask(const Scenario& scenario, double distance) {
  std::vector<bool> mask(size_t(scenario.width) * size_t(scenario.height), false);
  for (const Step& step : scenario.steps) {
    const auto* d = std::get_if<DrawStep>(&step);
    if (!d) continue;
    const Viewport& vp = d->state.viewport;
    for (size_t first = 0; first + 2 < d->vertices.size(); first += 3) {
      const Polygon p = clipTriangle(*d, first);
      if (p.size() < 3) continue;
      std::vector<glm::dvec2> window;
      for (const glm::dvec4& c : p)
        window.push_back({vp.x + (c.x / c.w + 1.0) * 0.5 * vp.width, vp.y + (c.y / c.w + 1.0) * 0.5 * vp.height});
      for (size_t i = 0; i < window.size(); ++i)
        markSegment(mask, scenario.width, scenario.height, window[i], window[(i + 1) % window.size()], distance);
    }
  }
  return mask;
}

}  // namespace shadowref::conformance
