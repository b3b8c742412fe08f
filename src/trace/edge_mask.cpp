#include "trace/edge_mask.h"

#include <algorithm>
#include <cmath>

namespace shadowref::trace {

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

double distanceToSegment(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
  const glm::dvec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

}  // namespace

void EdgeMask::addTriangle(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c, const Viewport& vp,
                           bool depthClamp, double distance) {
  Polygon p = {a, b, c};
  std::vector<glm::dvec4> planes = {{1, 0, 0, 4}, {-1, 0, 0, 4}, {0, 1, 0, 4}, {0, -1, 0, 4}, {0, 0, 0, 1}};
  if (!depthClamp) {
    planes.push_back({0, 0, 1, 1});   // near: z >= -w
    planes.push_back({0, 0, -1, 1});  // far: z <= w
  }
  for (const glm::dvec4& plane : planes) {
    if (p.size() < 3) return;
    p = clipAgainst(p, plane);
  }
  if (p.size() < 3) return;
  std::vector<glm::dvec2> window;
  for (const glm::dvec4& q : p) {
    if (!(q.w > 0.0)) return;  // on the w = 0 plane after clipping: nothing on screen
    window.push_back({vp.x + (q.x / q.w + 1.0) * 0.5 * vp.width, vp.y + (q.y / q.w + 1.0) * 0.5 * vp.height});
  }
  for (size_t i = 0; i < window.size(); ++i) {
    const glm::dvec2& s = window[i];
    const glm::dvec2& e = window[(i + 1) % window.size()];
    if (!std::isfinite(s.x) || !std::isfinite(s.y) || !std::isfinite(e.x) || !std::isfinite(e.y)) continue;
    // The segment's box, widened by the distance, cut to the framebuffer (in double: the
    // corners may lie far outside any int).
    const double fx0 = std::max(0.0, std::floor(std::min(s.x, e.x) - distance - 1));
    const double fx1 = std::min(double(width_ - 1), std::ceil(std::max(s.x, e.x) + distance + 1));
    const double fy0 = std::max(0.0, std::floor(std::min(s.y, e.y) - distance - 1));
    const double fy1 = std::min(double(height_ - 1), std::ceil(std::max(s.y, e.y) + distance + 1));
    if (fx0 > fx1 || fy0 > fy1) continue;
    for (int y = int(fy0); y <= int(fy1); ++y)
      for (int x = int(fx0); x <= int(fx1); ++x)
        if (distanceToSegment({x + 0.5, y + 0.5}, s, e) <= distance) mask_[size_t(y) * size_t(width_) + size_t(x)] = true;
  }
}

}  // namespace shadowref::trace
