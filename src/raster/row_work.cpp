#include "raster/row_work.h"

namespace shadowref {

void RowWork::addClear(const Rect& region) {
  if (region.width <= 0 || region.height <= 0) return;
  diff_[size_t(region.y)] += region.width / 4 + kRowCost;
  diff_[size_t(region.y + region.height)] -= region.width / 4 + kRowCost;
  touched(size_t(region.y), size_t(region.y + region.height));
}

void RowWork::add(const RowWork& other) {
  for (size_t r = other.lowest_; r <= other.highest_ && r < diff_.size(); ++r) diff_[r] += other.diff_[r];
  touched(other.lowest_, other.highest_);
}

int RowWork::split(int minY, int maxY, int maxBands, int minRows, std::vector<int>& firstRow) {
  // Each row's work from the differences; + 1 a row: no row is free, and no band is of no rows.
  std::vector<int64_t>& work = work_;
  work.resize(size_t(maxY - minY + 1));
  int64_t running = 0, total = 0;
  for (int y = 0; y <= maxY; ++y) {
    running += diff_[size_t(y)];
    if (y >= minY) total += work[size_t(y - minY)] = running + 1;
  }
  const size_t rows = work.size();
  const int64_t parts = int64_t(maxBands) * (maxBands + 3) / 2;  // (maxBands + 1) + … + 2
  firstRow.assign(1, minY);
  int64_t done = 0, partsUpTo = maxBands + 1;  // the parts of bands 0 … the current one
  size_t start = 0;
  for (size_t r = 0; r < rows; ++r) {
    done += work[r];
    const int band = int(firstRow.size()) - 1;
    const bool full = done * parts >= total * partsUpTo;  // this band has its share
    if (full && r + 1 - start >= size_t(minRows) && rows - (r + 1) >= size_t(minRows) && band + 1 < maxBands) {
      firstRow.push_back(minY + int(r) + 1);
      start = r + 1;
      partsUpTo += maxBands - band;  // band + 1's share: maxBands + 1 - (band + 1)
    }
  }
  firstRow.push_back(maxY + 1);
  return int(firstRow.size()) - 1;
}

}  // namespace shadowref
