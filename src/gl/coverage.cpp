#include "gl/coverage.h"

#include <algorithm>

namespace shadowref {

bool covers(const TriangleSetup& t, int x, int y, int64_t e[3]) {
  bool inside = true;
  for (int i = 0; i < 3; ++i) {
    e[i] = t.edgeAt(i, x, y);
    inside = inside && e[i] + t.bias[i] >= 0;  // the top-left rule: bias -1 excludes E = 0
  }
  return inside;
}

Rect candidatePixels(const TriangleSetup& t, const Rect& region) {
  const int x0 = std::max(t.minX, region.x), x1 = std::min(t.maxX, region.x + region.width - 1);
  const int y0 = std::max(t.minY, region.y), y1 = std::min(t.maxY, region.y + region.height - 1);
  if (x0 > x1 || y0 > y1) return Rect{};
  return Rect{x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

void coveredPixels(const TriangleSetup& t, const Rect& region, std::vector<CoveredPixel>& out) {
  out.clear();
  const Rect box = candidatePixels(t, region);
  for (int y = box.y; y < box.y + box.height; ++y) {
    for (int x = box.x; x < box.x + box.width; ++x) {
      CoveredPixel p{x, y, {}};
      if (covers(t, x, y, p.e)) out.push_back(p);
    }
  }
}

}  // namespace shadowref
