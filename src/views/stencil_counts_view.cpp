#include "views/stencil_counts_view.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "image/stencil_view.h"

namespace shadowref::views {

namespace {

std::string countText(int count, bool signedCounts) {
  return (signedCounts && count > 0 ? "+" : "") + std::to_string(count);
}

// About four evenly spaced ticks between lo and hi at round steps (1, 2, 5 times a power of ten),
// with lo, hi and 0 (when between them) always among them.
std::vector<int> rampTicks(int lo, int hi) {
  std::set<int> ticks = {lo, hi};
  if (lo < 0 && hi > 0) ticks.insert(0);
  const double raw = double(hi - lo) / 4.0;
  int step = 1;
  for (int p = 1; p <= 1000; p *= 10)
    for (int m : {1, 2, 5})
      if (step == 1 && double(m * p) >= raw) step = m * p;
  for (int v = (lo / step) * step; v < hi; v += step)
    if (v > lo) ticks.insert(v);
  return {ticks.begin(), ticks.end()};
}

}  // namespace

int stencilCountOf(uint8_t value, bool signedCounts) { return stencilCount(value, signedCounts); }

View stencilView(std::span<const uint8_t> stencil, int width, int height, const StencilViewSettings& settings) {
  if (width <= 0 || height <= 0 || stencil.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("stencil has " + std::to_string(stencil.size()) + " values for " + std::to_string(width) +
                                "x" + std::to_string(height) + " pixels");
  std::set<int> present;
  for (uint8_t v : stencil) present.insert(stencilCountOf(v, settings.signedCounts));
  View view;
  view.picture = filledPicture(width, height, {0, 0, 0});
  ViewLegend& legend = view.legend;
  legend.quantity = settings.signedCounts ? "stencil count (signed)" : "stencil count";
  const bool ramp = present.size() > settings.maxSwatches;
  const int lo = *present.begin(), hi = *present.rbegin();
  auto colourOf = [&](int count) -> Rgb8 {
    if (count == 0) return {0, 0, 0};
    if (!ramp) return stencilColour(count);
    return viridis(hi > lo ? double(count - lo) / double(hi - lo) : 0.5);
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      setBufferPixel(view.picture, x, y,
                     colourOf(stencilCountOf(stencil[size_t(y) * size_t(width) + size_t(x)], settings.signedCounts)));
  if (ramp) {
    legend.kind = LegendKind::Ramp;
    legend.lo = lo;
    legend.hi = hi;
    legend.values = rampTicks(lo, hi);
    legend.background = {0, 0, 0};  // count 0 stays black on the ramp too
    legend.hasBackground = present.count(0) > 0;
  } else {
    legend.kind = LegendKind::Swatches;
    legend.values.assign(present.begin(), present.end());
    for (int c : legend.values) legend.colours.push_back(colourOf(c));
  }
  for (int c : legend.values) legend.labels.push_back(countText(c, settings.signedCounts));
  return view;
}

}  // namespace shadowref::views
