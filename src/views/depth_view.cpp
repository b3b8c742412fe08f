#include "views/depth_view.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "shadow/trapezoid_overlay.h"
#include "views/value_label.h"

namespace shadowref::views {

namespace {

void checkSize(size_t values, int width, int height) {
  if (width <= 0 || height <= 0 || values != size_t(width) * size_t(height))
    throw std::invalid_argument("a view needs width x height values: " + std::to_string(values) + " for " +
                                std::to_string(width) + "x" + std::to_string(height));
}

// values[i] where covered[i], auto-ranged onto viridis over the covered values above `floor`
// (all covered values when none is above it); values below the range take its low end. The rest
// kNothingDrawn.
View rangedView(std::span<const double> values, std::span<const uint8_t> covered, int width, int height,
                const std::string& quantity, double floor = -std::numeric_limits<double>::infinity()) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (int pass = 0; pass < 2 && !(lo <= hi); ++pass)
    for (size_t i = 0; i < values.size(); ++i)
      if (covered[i] && (pass == 1 || values[i] > floor)) {
        lo = std::min(lo, values[i]);
        hi = std::max(hi, values[i]);
      }
  View view;
  view.picture = filledPicture(width, height, kNothingDrawn);
  view.legend.background = kNothingDrawn;
  const bool any = lo <= hi;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * size_t(width) + size_t(x);
      if (!covered[i]) {
        view.legend.hasBackground = true;
        continue;
      }
      // One value everywhere: the middle of the map, so that it reads as neither end.
      const double t = hi > lo ? std::max(0.0, (values[i] - lo) / (hi - lo)) : 0.5;
      setBufferPixel(view.picture, x, y, viridis(t));
    }
  if (!any) return view;
  view.legend.kind = LegendKind::ColourBar;
  view.legend.quantity = quantity;
  view.legend.lo = lo;
  view.legend.hi = hi;
  view.legend.labels = {rangeLabel(lo, lo, hi), rangeLabel(hi, lo, hi)};
  return view;
}

}  // namespace

double eyeDistance(double windowDepth, const glm::dmat4& P, const Viewport& viewport) {
  const double range = viewport.farVal - viewport.nearVal;
  const double zNdc = range != 0.0 ? 2.0 * (windowDepth - viewport.nearVal) / range - 1.0 : 0.0;
  const double zEye = (P[3][2] - zNdc * P[3][3]) / (zNdc * P[2][3] - P[2][2]);
  return -zEye;
}

View depthView(std::span<const float> windowDepth, int width, int height, const glm::dmat4& projection,
               const Viewport& viewport) {
  checkSize(windowDepth.size(), width, height);
  std::vector<double> distance(windowDepth.size());
  std::vector<uint8_t> covered(windowDepth.size());
  for (size_t i = 0; i < windowDepth.size(); ++i) {
    covered[i] = windowDepth[i] < 1.0f;  // NaN is not covered either
    if (covered[i]) distance[i] = eyeDistance(windowDepth[i], projection, viewport);
  }
  return rangedView(distance, covered, width, height, "eye depth");
}

View shadowMapView(std::span<const float> depth, int width, int height) {
  checkSize(depth.size(), width, height);
  std::vector<double> values(depth.begin(), depth.end());
  std::vector<uint8_t> covered(depth.size());
  for (size_t i = 0; i < depth.size(); ++i) covered[i] = depth[i] < 1.0f;
  // Depth 0 does not widen the range: a TSM map clamps the casters nearer the light than its
  // focus body to 0 (light_shadow.h), and the .plain view draws the trapezoid with 0.
  return rangedView(values, covered, width, height, "stored depth", 0.0);
}

namespace {

// The part of the segment a..b (clip space) where every plane p has dot(p, point) >= 0
// (Liang-Barsky in homogeneous coordinates); false when nothing is left.
bool clipSegment(glm::dvec4& a, glm::dvec4& b) {
  // -w <= x <= w, -w <= y <= w, and w above a sliver in front of the light (a perspective light's
  // points behind it have w < 0 and project through infinity).
  const double wMin = 1e-9 * std::max(std::abs(a.w), std::abs(b.w));
  const std::array<glm::dvec4, 5> planes{glm::dvec4(-1, 0, 0, 1), glm::dvec4(1, 0, 0, 1), glm::dvec4(0, -1, 0, 1),
                                         glm::dvec4(0, 1, 0, 1), glm::dvec4(0, 0, 0, 1)};
  double t0 = 0.0, t1 = 1.0;
  for (size_t i = 0; i < planes.size(); ++i) {
    const double offset = i == 4 ? -wMin : 0.0;
    const double da = glm::dot(planes[i], a) + offset, db = glm::dot(planes[i], b) + offset;
    if (da < 0.0 && db < 0.0) return false;
    if (da < 0.0) t0 = std::max(t0, da / (da - db));
    else if (db < 0.0) t1 = std::min(t1, da / (da - db));
  }
  if (!(t0 <= t1)) return false;
  const glm::dvec4 from = a, to = b;
  a = from + (to - from) * t0;
  b = from + (to - from) * t1;
  return true;
}

void drawMapLine(View& view, const glm::dvec2& a, const glm::dvec2& b, Rgb8 colour) {
  forEachLineTexel(view.picture.width, view.picture.height, a, b,
                   [&](int x, int y) { setBufferPixel(view.picture, x, y, colour); });
}

}  // namespace

void drawShadowMapOutline(View& view, const ShadowMapOutline& outline) {
  std::array<glm::dvec4, 8> clip;
  for (size_t i = 0; i < 8; ++i) clip[i] = outline.worldToClip * glm::dvec4(outline.frustum[i], 1.0);
  const auto edge = [&](size_t i, size_t j) {
    glm::dvec4 a = clip[i], b = clip[j];
    if (!clipSegment(a, b)) return;
    drawMapLine(view, glm::dvec2(a) / a.w, glm::dvec2(b) / b.w, kFrustumColour);
  };
  for (size_t i = 0; i < 4; ++i) {
    edge(i, (i + 1) % 4);          // the near plane
    edge(4 + i, 4 + (i + 1) % 4);  // the far plane
    edge(i, 4 + i);                // near to far
  }
  const std::vector<glm::dvec2>& t = outline.trapezoid;
  for (size_t i = 0; i < t.size(); ++i) drawMapLine(view, t[i], t[(i + 1) % t.size()], kTrapezoidColour);
  view.legend.outlines.push_back({"camera frustum", kFrustumColour});
  if (!t.empty()) view.legend.outlines.push_back({"trapezoid", kTrapezoidColour});
}

}  // namespace shadowref::views
