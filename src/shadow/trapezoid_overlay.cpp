#include "shadow/trapezoid_overlay.h"

#include <algorithm>
#include <cmath>

namespace shadowref {

namespace {

glm::dvec2 toTexel(const DepthTexture& map, const glm::dvec2& p) {
  return {(p.x + 1.0) * 0.5 * map.width, (p.y + 1.0) * 0.5 * map.height};
}

void plot(DepthTexture& map, double x, double y, float value) {
  const double fx = std::floor(x), fy = std::floor(y);
  if (fx < 0.0 || fy < 0.0 || fx >= map.width || fy >= map.height) return;
  map.set(int(fx), int(fy), value);
}

// A line sampled at half-texel steps: dense enough to leave no gaps.
void drawLine(DepthTexture& map, const glm::dvec2& a, const glm::dvec2& b, float value) {
  const glm::dvec2 ta = toTexel(map, a), tb = toTexel(map, b);
  const double length = glm::length(tb - ta);
  if (!std::isfinite(length)) return;
  const int steps = std::clamp(int(std::ceil(2.0 * length)), 1, 4 * (map.width + map.height));
  for (int i = 0; i <= steps; ++i) {
    const glm::dvec2 p = ta + (tb - ta) * (double(i) / steps);
    plot(map, p.x, p.y, value);
  }
}

}  // namespace

void drawTrapezoidOutline(DepthTexture& map, const Trapezoid& trapezoid, float value) {
  for (size_t i = 0; i < 4; ++i) drawLine(map, trapezoid.t[i], trapezoid.t[(i + 1) % 4], value);
  if (trapezoid.fallback || trapezoid.parallelSides) return;
  const glm::dvec2 f = toTexel(map, trapezoid.focusPoint);
  for (int d = -3; d <= 3; ++d) {
    plot(map, f.x + d, f.y, value);
    plot(map, f.x, f.y + d, value);
  }
}

}  // namespace shadowref
