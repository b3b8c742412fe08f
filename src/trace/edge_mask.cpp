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

void NearCutBound::addTriangle(const glm::dvec4& a, const glm::dvec4& b, const glm::dvec4& c, const RenderState& state) {
  if (state.depthClamp) return;
  const glm::dvec4 corners[3] = {a, b, c};
  bool inFront = false, behind = false;
  for (const glm::dvec4& p : corners) (p.z + p.w >= 0.0 ? inFront : behind) = true;
  if (!inFront || !behind) return;
  const Viewport& vp = state.viewport;
  const double halfW = 0.5 * vp.width, halfH = 0.5 * vp.height, halfZ = 0.5 * std::fabs(vp.farVal - vp.nearVal);
  auto window = [&](const glm::dvec4& q) {
    return glm::dvec3(vp.x + (q.x / q.w + 1.0) * halfW, vp.y + (q.y / q.w + 1.0) * halfH,
                      vp.nearVal + (q.z / q.w + 1.0) * 0.5 * (vp.farVal - vp.nearVal));
  };
  // The cut triangle in double, inside the view volume's x, y planes (where its pixels are).
  Polygon p = {a, b, c};
  for (const glm::dvec4& plane : {glm::dvec4(0, 0, 1, 1), glm::dvec4(1, 0, 0, 1), glm::dvec4(-1, 0, 0, 1),
                                  glm::dvec4(0, 1, 0, 1), glm::dvec4(0, -1, 0, 1), glm::dvec4(0, 0, -1, 1)}) {
    if (p.size() < 3) return;
    p = clipAgainst(p, plane);
  }
  if (p.size() < 3) return;
  std::vector<glm::dvec3> w;
  for (const glm::dvec4& q : p) {
    if (!(q.w > 0.0)) return;
    w.push_back(window(q));
  }
  // The plane's slopes from the polygon's largest corner triangle (all lie in one plane).
  double dzdx = 0.0, dzdy = 0.0, bestDet = 0.0;
  for (size_t k = 1; k + 1 < w.size(); ++k) {
    const glm::dvec3 e1 = w[k] - w[0], e2 = w[k + 1] - w[0];
    const double det = e1.x * e2.y - e2.x * e1.y;
    if (std::fabs(det) <= bestDet) continue;
    bestDet = std::fabs(det);
    dzdx = (e1.z * e2.y - e2.z * e1.y) / det;
    dzdy = (e1.x * e2.z - e2.x * e1.z) / det;
  }
  if (!(bestDet > 0.0) || !std::isfinite(dzdx) || !std::isfinite(dzdy)) return;
  double bound = 0.0;
  for (int i = 0; i < 3; ++i) {
    const glm::dvec4& s = corners[i];
    const glm::dvec4& e = corners[(i + 1) % 3];
    const double ds = s.z + s.w, de = e.z + e.w;
    if ((ds >= 0.0) == (de >= 0.0)) continue;
    const glm::dvec4 v = s + (e - s) * (ds / (ds - de));
    if (!(v.w > 0.0)) continue;  // cut behind the eye: outside the view volume anyway
    const glm::dvec4 m = glm::max(glm::abs(s), glm::abs(e));
    const double err = 0x1p-22 * std::max({m.x, m.y, m.z, m.w});
    auto ndcError = [&](double coordinate) { return err * (1.0 + std::fabs(coordinate / v.w)) / v.w; };
    const double codes = (halfZ * ndcError(v.z) + std::fabs(dzdx) * halfW * ndcError(v.x) +
                          std::fabs(dzdy) * halfH * ndcError(v.y)) * 16777215.0;
    bound = std::max(bound, codes);
  }
  if (state.polygonOffset.enabled)
    bound += std::fabs(state.polygonOffset.factor) * std::max(std::fabs(dzdx), std::fabs(dzdy)) * 16777215.0;
  if (!std::isfinite(bound)) bound = 16777215.0;
  // The pixel centres inside the convex polygon (either winding).
  double x0 = w[0].x, x1 = w[0].x, y0 = w[0].y, y1 = w[0].y;
  for (const glm::dvec3& q : w) {
    x0 = std::min(x0, q.x);
    x1 = std::max(x1, q.x);
    y0 = std::min(y0, q.y);
    y1 = std::max(y1, q.y);
  }
  const double fx0 = std::max(0.0, std::floor(x0)), fx1 = std::min(double(width_ - 1), std::ceil(x1));
  const double fy0 = std::max(0.0, std::floor(y0)), fy1 = std::min(double(height_ - 1), std::ceil(y1));
  if (fx0 > fx1 || fy0 > fy1) return;
  for (int y = int(fy0); y <= int(fy1); ++y)
    for (int x = int(fx0); x <= int(fx1); ++x) {
      const double px = x + 0.5, py = y + 0.5;
      bool pos = false, neg = false;
      for (size_t k = 0; k < w.size(); ++k) {
        const glm::dvec3& s = w[k];
        const glm::dvec3& e = w[(k + 1) % w.size()];
        const double side = (e.x - s.x) * (py - s.y) - (e.y - s.y) * (px - s.x);
        if (side > 0.0) pos = true;
        if (side < 0.0) neg = true;
      }
      if (pos && neg) continue;
      double& slot = codes_[size_t(y) * size_t(width_) + size_t(x)];
      slot = std::max(slot, bound);
    }
}

}  // namespace shadowref::trace
