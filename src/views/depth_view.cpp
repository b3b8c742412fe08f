#include "views/depth_view.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

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

}  // namespace shadowref::views
