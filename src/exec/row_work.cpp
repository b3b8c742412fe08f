#include "exec/row_work.h"

#include "gl/fragment_ops.h"

namespace shadowref {

int fragmentWorkOf(const FragmentShader* shader) {
  constexpr int kInterpolatedColor = 4;  // RGBA
  if (!shader || shader->constantColor() || shader->varyingCount() <= kInterpolatedColor) return kPlainFragmentWork;
  return 3 * kPlainFragmentWork;
}

void RowWork::addClear(const Rect& region) {
  if (region.width <= 0 || region.height <= 0) return;
  diff_[size_t(region.y)] += (region.width / 4 + kRowCost) * kUnit;
  diff_[size_t(region.y + region.height)] -= (region.width / 4 + kRowCost) * kUnit;
  touched(size_t(region.y), size_t(region.y + region.height));
}

// A ramp is two entries of each list: the first row's weight and the step after it, then both
// taken back after the last row (by the same integers, so the rows after it weigh nothing).
void RowWork::addRamp(int first, int last, int64_t start, int64_t step, int bottom, int top) {
  if (first < bottom) {
    start += step * (bottom - first);
    first = bottom;
  }
  last = std::min(last, top);
  if (first > last) return;
  diff_[size_t(first)] += start;
  slope_[size_t(first) + 1] += step;
  slope_[size_t(last) + 1] -= step;
  diff_[size_t(last) + 1] -= start + step * (last - first);
  touched(size_t(first), size_t(last) + 1);
}

// The triangle's width grows from its top row to the middle vertex's row and falls to its bottom
// row: about 2 × area / rows at the peak (the rows' mean is half the peak's). Each side is a ramp,
// and where it would be wider than the region, a flat run at the region's width.
void RowWork::addShape(const SetupBounds& t, const TriangleSetup& setup, int bottom, int top, int64_t width,
                       int64_t pixel) {
  const int64_t rows = int64_t(t.maxY) - t.minY + 1;
  // The peak's 2 × area × kUnit from area2, twice the area in 1/256² of a pixel: area2 × 2^9 /
  // 2^17, shifted down rather than multiplied up (area2 reaches 2^58 in the guard band); then
  // weighed as its pixels are (pixel / kUnit: exact for a plain pixel).
  const int64_t plainPeak = std::max<int64_t>((setup.area2 >> (2 * kSubpixelBits - 8)) / rows, kUnit);
  const int64_t peak = plainPeak * pixel / kUnit;
  // The widest row: the one whose centre is nearest the middle vertex (>> floors, also below 0).
  const int64_t y0 = setup.v[0].y, y1 = setup.v[1].y, y2 = setup.v[2].y;
  const int64_t middle = y0 + y1 + y2 - std::min({y0, y1, y2}) - std::max({y0, y1, y2});
  const int peakY = std::clamp(int(middle >> kSubpixelBits), t.minY, t.maxY);
  const int64_t cap = width * pixel;
  // Rising: rows minY … peakY weigh rise × 1, 2, …, n (n = peakY - minY + 1).
  const int64_t n = int64_t(peakY) - t.minY + 1;
  const int64_t rise = std::max<int64_t>(peak / n, 1);
  const int64_t belowCap = std::min(n, (cap - 1) / rise);  // the rows under the cap: rise × k < cap
  addRamp(t.minY, t.minY + int(belowCap) - 1, rise, rise, bottom, top);
  addRamp(t.minY + int(belowCap), peakY, cap, 0, bottom, top);
  // Falling: rows peakY + 1 … maxY weigh fall × m, …, 2, 1 (m = maxY - peakY).
  const int64_t m = int64_t(t.maxY) - peakY;
  if (m == 0) return;
  const int64_t fall = std::max<int64_t>(peak / (m + 1), 1);
  const int64_t underCap = std::min(m, (cap - 1) / fall);  // the last rows, fall × k < cap
  addRamp(peakY + 1, t.maxY - int(underCap), cap, 0, bottom, top);
  addRamp(t.maxY - int(underCap) + 1, t.maxY, fall * underCap, -fall, bottom, top);
}

// On the calling thread, between the assembly's run and the bands' (a flush adds a list per
// assembly task): one bound, computed first, so that the loop vectorises.
void RowWork::add(const RowWork& other) {
  const size_t end = std::min(other.highest_ + 1, diff_.size());
  int64_t* const diff = diff_.data();
  int64_t* const slope = slope_.data();
  const int64_t* const otherDiff = other.diff_.data();
  const int64_t* const otherSlope = other.slope_.data();
  for (size_t r = other.lowest_; r < end; ++r) {
    diff[r] += otherDiff[r];
    slope[r] += otherSlope[r];
  }
  touched(other.lowest_, other.highest_);
}

// Each row's work from the differences; + 1 pixel a row: no row is free, and no band is of no rows.
int64_t RowWork::weigh(int minY, int maxY, std::vector<int64_t>& work) const {
  work.resize(size_t(maxY - minY + 1));
  int64_t step = 0, running = 0, total = 0;
  for (int y = 0; y <= maxY; ++y) {
    step += slope_[size_t(y)];
    running += diff_[size_t(y)] + step;
    if (y < minY) continue;
    int64_t row = running + kUnit;
    const size_t sample = size_t(y - stencilFirstRow_) / kStencilSampleRows;
    if (y >= stencilFirstRow_ && sample < stencilScale_.size()) row = row * stencilScale_[sample] / 16;
    total += work[size_t(y - minY)] = row;
  }
  return total;
}

// A sampled row's masked values counted below, at and above the test's masked reference, in a
// loop without branches (it vectorises: 80 rows of 800 bytes a flush, on the calling thread); the
// test's compare function (fragment_ops.h) then says which of the three pass, asked with one value
// of each: it reads only their order.
void RowWork::weighByStencil(const uint8_t* stencil, int width, int minY, int maxY, const StencilFaceState& test) {
  stencilScale_.clear();
  stencilFirstRow_ = minY;
  const uint8_t mask = test.mask;
  const uint8_t ref = uint8_t(maskedStencilReference(test));
  const bool passBelow = ref > 0 && compare(test.func, ref, uint32_t(ref) - 1);
  const bool passAt = compare(test.func, ref, ref);
  const bool passAbove = ref < mask && compare(test.func, ref, uint32_t(ref) + 1);
  for (int y = minY; y <= maxY; y += kStencilSampleRows) {
    const uint8_t* row = stencil + size_t(y) * size_t(width);
    int32_t below = 0, at = 0;
    for (int x = 0; x < width; ++x) {
      const uint8_t value = row[x] & mask;
      below += value < ref;
      at += value == ref;
    }
    const int64_t passing = (passBelow ? below : 0) + (passAt ? at : 0) + (passAbove ? width - below - at : 0);
    stencilScale_.push_back(4 + 12 * passing / std::max(width, 1));
  }
}

std::vector<int64_t> RowWork::rowWeights(int minY, int maxY) const {
  std::vector<int64_t> work;
  weigh(minY, maxY, work);
  return work;
}

int RowWork::split(int minY, int maxY, int maxBands, int minRows, std::vector<int>& firstRow, Shares shares) {
  std::vector<int64_t>& work = work_;
  const int64_t total = weigh(minY, maxY, work);
  const size_t rows = work.size();
  const bool equal = shares == Shares::Equal;
  // Shrinking: band b of n takes n + 1 - b parts of (n + 1) + … + 2; equal: one part of n.
  const int64_t parts = equal ? maxBands : int64_t(maxBands) * (maxBands + 3) / 2;
  firstRow.assign(1, minY);
  int64_t done = 0, partsUpTo = equal ? 1 : maxBands + 1;  // the parts of bands 0 … the current one
  size_t start = 0;
  for (size_t r = 0; r < rows; ++r) {
    done += work[r];
    const int band = int(firstRow.size()) - 1;
    const bool full = done * parts >= total * partsUpTo;  // this band has its share
    if (full && r + 1 - start >= size_t(minRows) && rows - (r + 1) >= size_t(minRows) && band + 1 < maxBands) {
      firstRow.push_back(minY + int(r) + 1);
      start = r + 1;
      partsUpTo += equal ? 1 : maxBands - band;  // band + 1's share: maxBands + 1 - (band + 1)
    }
  }
  firstRow.push_back(maxY + 1);
  return int(firstRow.size()) - 1;
}

}  // namespace shadowref
