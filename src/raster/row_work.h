// The work a flush's rows are expected to take, and their split into bands of rows for the
// threads (Renderer::flush). Only the split depends on it: every split gives the same bytes, so the
// estimate is free to be rough; it must be cheap, because it looks at every pending triangle.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "raster/render_state.h"

namespace shadowref {

class RowWork {
 public:
  // Forgets every triangle and clear, for a framebuffer of `rows` rows: zeroes what was written
  // (a flush resets a list per assembly task, of 2049 entries for a 2048² map).
  void reset(int rows) {
    if (diff_.size() != size_t(rows) + 1) diff_.assign(size_t(rows) + 1, 0);
    else if (lowest_ <= highest_) std::fill(diff_.begin() + std::ptrdiff_t(lowest_), diff_.begin() + std::ptrdiff_t(highest_) + 1, 0);
    lowest_ = diff_.size();
    highest_ = 0;
  }

  // A triangle whose bounding box is [minX, maxX] x [minY, maxY], drawn inside `region`: its
  // width on each of its rows and a row's fixed cost, once its fixed cost. A difference list (each
  // triangle writes three entries, not one per row), so that a group of triangles on one thread can
  // be counted on its own and added to the others (add).
  void addTriangle(int minX, int minY, int maxX, int maxY, const Rect& region) {
    const int top = std::min(maxY, region.y + region.height - 1), bottom = std::max(minY, region.y);
    const int64_t width = int64_t(std::min(maxX, region.x + region.width - 1)) - std::max(minX, region.x) + 1;
    if (bottom > top || width <= 0) return;
    diff_[size_t(bottom)] += width + kRowCost + kTriangleCost;
    diff_[size_t(bottom) + 1] -= kTriangleCost;
    diff_[size_t(top) + 1] -= width + kRowCost;
    touched(size_t(bottom), size_t(top) + 1);
  }
  // A cleared rectangle: a cleared row costs about a quarter of a drawn one.
  void addClear(const Rect& region);
  // Another count over the same rows (only the entries it wrote: with many threads a flush adds
  // many groups' lists, each over a few of the rows).
  void add(const RowWork& other);

  // Cuts rows [minY, maxY] into at most maxBands bands, each at least minRows rows (unless all of
  // them are fewer): fills firstRow (band b is rows [firstRow[b], firstRow[b + 1])), returns the
  // count. The threads take the bands in order, so the bands get shrinking shares of the estimated
  // work — maxBands + 1, maxBands, … 2 parts — and the last ones, small, even out the threads'
  // ends. The city's shadow volumes crowd into the lower rows: equal rows would leave one thread
  // most of them.
  int split(int minY, int maxY, int maxBands, int minRows, std::vector<int>& firstRow);

 private:
  // A row's and a triangle's fixed costs, in pixels.
  static constexpr int64_t kRowCost = 8, kTriangleCost = 64;
  std::vector<int64_t> diff_;  // per row, what its work adds to the row above's
  std::vector<int64_t> work_;  // split's: the work of each of its rows
  size_t lowest_ = 0, highest_ = 0;  // the entries of diff_ written since reset: [lowest_, highest_]
  void touched(size_t first, size_t last) {
    lowest_ = std::min(lowest_, first);
    highest_ = std::max(highest_, last);
  }
};

}  // namespace shadowref
