#include "shadow/trapezoid_overlay.h"

#include <algorithm>
#include <cmath>

namespace shadowref {

namespace {

glm::dvec2 toTexel(int width, int height, const glm::dvec2& p) {
  return {(p.x + 1.0) * 0.5 * width, (p.y + 1.0) * 0.5 * height};
}

void plot(DepthTexture& map, double x, double y, float value) {
  const double fx = std::floor(x), fy = std::floor(y);
  if (fx < 0.0 || fy < 0.0 || fx >= map.width || fy >= map.height) return;
  map.set(int(fx), int(fy), value);
}

}  // namespace

void forEachLineTexel(int width, int height, const glm::dvec2& a, const glm::dvec2& b,
                      const std::function<void(int x, int y)>& texel) {
  const glm::dvec2 ta = toTexel(width, height, a), tb = toTexel(width, height, b);
  const double length = glm::length(tb - ta);
  if (!std::isfinite(length)) return;
  const int steps = std::clamp(int(std::ceil(2.0 * length)), 1, 4 * (width + height));
  for (int i = 0; i <= steps; ++i) {
    const glm::dvec2 p = ta + (tb - ta) * (double(i) / steps);
    const double fx = std::floor(p.x), fy = std::floor(p.y);
    if (fx < 0.0 || fy < 0.0 || fx >= width || fy >= height) continue;
    texel(int(fx), int(fy));
  }
}

void drawTrapezoidOutline(DepthTexture& map, const Trapezoid& trapezoid, float value) {
  for (size_t i = 0; i < 4; ++i)
    forEachLineTexel(map.width, map.height, trapezoid.t[i], trapezoid.t[(i + 1) % 4],
                     [&](int x, int y) { map.set(x, y, value); });
  if (trapezoid.fallback || trapezoid.parallelSides) return;
  const glm::dvec2 f = toTexel(map.width, map.height, trapezoid.focusPoint);
  for (int d = -3; d <= 3; ++d) {
    plot(map, f.x + d, f.y, value);
    plot(map, f.x, f.y + d, value);
  }
}

}  // namespace shadowref
