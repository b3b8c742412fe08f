#include "oracle/screen_bins.h"

#include <algorithm>
#include <cmath>

namespace shadowref::oracle {

ScreenBins::ScreenBins(const CameraModel& camera, const WorldVolumes& volumes) {
  const Viewport& vp = camera.viewport;
  columns_ = (vp.width + kTile - 1) / kTile;
  rows_ = (vp.height + kTile - 1) / kTile;
  tiles_.resize(static_cast<size_t>(columns_) * rows_);
  for (uint32_t i = 0; i < volumes.triangles.size(); ++i) {
    const ProjectiveTriangle& t = volumes.triangles[i].triangle;
    const std::vector<glm::dvec4> clipped =
        clipPolygonToView({camera.toClip(t.v[0]), camera.toClip(t.v[1]), camera.toClip(t.v[2])});
    if (clipped.empty()) continue;
    glm::dvec2 lo(HUGE_VAL), hi(-HUGE_VAL);
    for (const glm::dvec4& c : clipped) {
      const glm::dvec2 w = camera.toWindow(c);
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
    // Pixels (relative to the viewport) whose centre lies within one pixel of the box.
    const int x0 = std::max(0, static_cast<int>(std::floor(lo.x - vp.x - 1.5)));
    const int y0 = std::max(0, static_cast<int>(std::floor(lo.y - vp.y - 1.5)));
    const int x1 = std::min(vp.width - 1, static_cast<int>(std::ceil(hi.x - vp.x + 0.5)));
    const int y1 = std::min(vp.height - 1, static_cast<int>(std::ceil(hi.y - vp.y + 0.5)));
    if (x0 > x1 || y0 > y1) continue;
    for (int ty = y0 / kTile; ty <= y1 / kTile; ++ty)
      for (int tx = x0 / kTile; tx <= x1 / kTile; ++tx) tiles_[ty * columns_ + tx].push_back(i);
  }
}

}  // namespace shadowref::oracle
