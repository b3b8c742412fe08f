// Coverage: walks a set-up triangle over a pixel region and hands every covered pixel centre to
// a sink, with the three edge-function values there. Two forms of one decision:
// rasterizeSpans, row intervals, which the renderer uses; and rasterizeTriangle, pixel by pixel,
// which the one-fragment-at-a-time mode (Renderer::oneFragmentAtATime) and the pixel history's
// tests use.
//
// rasterizeTriangle visits the region in 8x8 blocks. A block is skipped when one edge is negative at all four
// of its corner samples (edge functions are linear, so then it is negative everywhere inside),
// and tested pixel by pixel otherwise. Inside a block the edge functions are stepped with integer
// additions only, so the coverage decision is exact and the same in every block order.
#pragma once

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "gl/render_state.h"
#include "gl/triangle_setup.h"

namespace shadowref {

inline constexpr int kRasterBlock = 8;

// Sink: void(int x, int y, int64_t e0, int64_t e1, int64_t e2). Pixels are delivered row by row,
// bottom to top, left to right within a block row. `region` is in pixels, inclusive-exclusive.
template <class Sink>
void rasterizeTriangle(const TriangleSetup& t, const Rect& region, Sink&& sink) {
  const int x0 = std::max(t.minX, region.x), x1 = std::min(t.maxX, region.x + region.width - 1);
  const int y0 = std::max(t.minY, region.y), y1 = std::min(t.maxY, region.y + region.height - 1);
  if (x0 > x1 || y0 > y1) return;

  for (int by = y0; by <= y1; by += kRasterBlock) {
    const int bh = std::min(kRasterBlock, y1 - by + 1);
    int64_t rowStart[3];
    for (int i = 0; i < 3; ++i) rowStart[i] = t.edgeAt(i, x0, by) + t.bias[i];
    for (int bx = x0; bx <= x1; bx += kRasterBlock) {
      const int bw = std::min(kRasterBlock, x1 - bx + 1);
      int64_t e[3];
      bool empty = false, full = true;
      for (int i = 0; i < 3; ++i) {
        e[i] = rowStart[i] + t.stepX[i] * (bx - x0);
        const int64_t dx = t.stepX[i] * (bw - 1), dy = t.stepY[i] * (bh - 1);
        const int64_t lo = e[i] + std::min<int64_t>(0, dx) + std::min<int64_t>(0, dy);
        const int64_t hi = e[i] + std::max<int64_t>(0, dx) + std::max<int64_t>(0, dy);
        if (hi < 0) empty = true;
        if (lo < 0) full = false;
      }
      if (empty) continue;
      for (int y = by; y < by + bh; ++y) {
        int64_t a = e[0], b = e[1], c = e[2];
        for (int x = bx; x < bx + bw; ++x) {
          if (full || (a >= 0 && b >= 0 && c >= 0))
            sink(x, y, a - t.bias[0], b - t.bias[1], c - t.bias[2]);
          a += t.stepX[0];
          b += t.stepX[1];
          c += t.stepX[2];
        }
        e[0] += t.stepY[0];
        e[1] += t.stepY[1];
        e[2] += t.stepY[2];
      }
    }
  }
}

// Columns [first, last] of the region that hold every pixel the triangle covers in rows [y0, y1]
// (inside its bounding box and the region; first > last when it covers none there): the x extent
// of the triangle cut to the rows' sample lines — its vertices between them and its edges' crossings
// of them — one pixel wider each side for the rounding of the crossings (worked in doubles). A
// triangle reaching across the screen but cut into bands of rows covers far fewer columns in each.
struct ColumnRange {
  int first = 0, last = -1;
};
inline ColumnRange columnsInRows(const TriangleSetup& t, const Rect& region, int y0, int y1) {
  const int64_t low = int64_t(y0) * kSubpixelOne + kSubpixelHalf, high = int64_t(y1) * kSubpixelOne + kSubpixelHalf;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  auto take = [&](double x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  };
  for (int i = 0; i < 3; ++i) {
    const WindowVertex& a = t.v[i];
    const WindowVertex& b = t.v[(i + 1) % 3];
    if (a.y >= low && a.y <= high) take(double(a.x));
    if (a.y == b.y) continue;
    for (const int64_t line : {low, high})
      if (line >= std::min(a.y, b.y) && line <= std::max(a.y, b.y))  // the edge meets the sample line
        take(double(a.x) + double(b.x - a.x) * (double(line - a.y) / double(b.y - a.y)));
  }
  ColumnRange c;
  if (!(lo <= hi)) return c;
  const double one = double(kSubpixelOne), half = double(kSubpixelHalf);
  // A centre px + 1/2 inside [lo, hi]: px from ceil(lo - 1/2) to floor(hi - 1/2).
  c.first = std::max({t.minX, region.x, int(std::max(std::ceil((lo - half) / one) - 1.0, double(INT32_MIN / 2)))});
  c.last = std::min({t.maxX, region.x + region.width - 1,
                     int(std::min(std::floor((hi - half) / one) + 1.0, double(INT32_MAX / 2)))});
  return c;
}

// Floor division for a positive divisor.
inline int64_t floorDiv(int64_t a, int64_t d) {
  const int64_t q = a / d;
  return (a % d != 0 && a < 0) ? q - 1 : q;
}

// One edge's limit on the covered columns of a row, stepped from row to row without division:
// the limit is floor(A / d) for a numerator A that changes by a fixed amount per row, so its
// quotient and remainder advance by a precomputed quotient and remainder (Bresenham's idea). A
// left edge (stepX > 0) gives the first covered offset ceil(-E / stepX), a right edge
// (stepX < 0) the last, floor(E / -stepX); E is the biased edge value at the row's first column.
struct EdgeLimit {
  int64_t q = 0, r = 0;    // floor(A / d) and A - q * d, 0 <= r < d
  int64_t dq = 0, dr = 0;  // the same for the change of A per row
  int64_t d = 1;

  void start(int64_t a, int64_t perRow, int64_t divisor) {
    d = divisor;
    q = floorDiv(a, d);
    r = a - q * d;
    dq = floorDiv(perRow, d);
    dr = perRow - dq * d;
  }
  void nextRow() {
    q += dq;
    r += dr;
    const int64_t wrap = r >= d;  // without a branch: the wrap is taken about every other row
    q += wrap;
    r -= d & -wrap;
  }
};

namespace detail {

// The row loop of rasterizeSpans for any triangle: up to three limits a side, horizontal edges
// tested on their edge values; the edge values at the span start computed only when the sink
// takes them.
template <bool WithEdges, class SpanSink>
void spanRows(const TriangleSetup& t, int x0, int y0, int y1, int64_t width, int64_t row[3], EdgeLimit* left,
              int lefts, EdgeLimit* right, int rights, const int* flat, int flats, SpanSink& sink) {
  const bool trackRows = WithEdges || flats > 0;
  for (int y = y0; y <= y1; ++y) {
    int64_t lo = left[0].q, hi = std::min(width, right[0].q);
    for (int k = 1; k < lefts; ++k) lo = std::max(lo, left[k].q);
    for (int k = 1; k < rights; ++k) hi = std::min(hi, right[k].q);
    lo = std::max<int64_t>(lo, 0);
    for (int k = 0; k < flats; ++k)
      if (row[flat[k]] < 0) hi = -1;
    if (lo <= hi) {
      if constexpr (WithEdges) {
        int64_t e[3];
        for (int i = 0; i < 3; ++i) e[i] = row[i] + t.stepX[i] * lo - t.bias[i];
        sink(y, x0 + int(lo), x0 + int(hi), e);
      } else {
        sink(y, x0 + int(lo), x0 + int(hi));
      }
    }
    if (trackRows)
      for (int i = 0; i < 3; ++i) row[i] += t.stepY[i];
    for (int k = 0; k < lefts; ++k) left[k].nextRow();
    for (int k = 0; k < rights; ++k) right[k].nextRow();
  }
}

// The same for one limit a side (rowsAroundMiddle's parts), with the limits, the edge values and
// the steps in locals through the loop: the sink's byte stores may alias anything, so values
// reached through pointers would go to memory and back every row.
template <bool WithEdges, class SpanSink>
void spanRowsOfTwo(const TriangleSetup& t, int x0, int y0, int y1, int64_t width, int64_t row[3], EdgeLimit& left,
                   EdgeLimit& right, SpanSink& sink) {
  EdgeLimit l = left, r = right;
  int64_t edges[3], stepX[3], stepY[3], bias[3];
  for (int i = 0; i < 3; ++i) {
    edges[i] = row[i];
    stepX[i] = t.stepX[i];
    stepY[i] = t.stepY[i];
    bias[i] = t.bias[i];
  }
  for (int y = y0; y <= y1; ++y) {
    const int64_t lo = std::max<int64_t>(l.q, 0), hi = std::min(width, r.q);
    if (lo <= hi) {
      if constexpr (WithEdges) {
        int64_t e[3];
        for (int i = 0; i < 3; ++i) e[i] = edges[i] + stepX[i] * lo - bias[i];
        sink(y, x0 + int(lo), x0 + int(hi), e);
      } else {
        sink(y, x0 + int(lo), x0 + int(hi));
      }
    }
    if constexpr (WithEdges)
      for (int i = 0; i < 3; ++i) edges[i] += stepY[i];
    l.nextRow();
    r.nextRow();
  }
  left = l;
  right = r;
  for (int i = 0; i < 3; ++i) row[i] = edges[i];
}

// Starts an edge's limit at the row whose biased edge value at the first column is `value`.
inline void startLimit(EdgeLimit& limit, const TriangleSetup& t, int i, int64_t value) {
  const int64_t s = t.stepX[i];
  if (s > 0) limit.start(-value + s - 1, -t.stepY[i], s);  // ceil(-E / s)
  else limit.start(value, t.stepY[i], -s);                 // floor(E / -s)
}

// The rows of a triangle with no horizontal edge: one edge on one side, two on the other, which
// meet at the middle vertex M. A row whose sample line is below M's needs only the lower of the
// two, one at or above it only the upper — two EdgeLimits a row, not three. Below M, inside the
// heights between the lowest vertex B and M, the wedge of the single edge and the lower one (both
// through B) is the triangle itself, strictly inside the upper edge's half-plane (E_upper >= 1
// there, so its bias changes nothing); likewise above M. On M's own sample line both edges cross
// at M with the same bias (edges of one side are both left or both right edges), so either limits
// that row alike. An edge's limit is started at the first row it is stepped from: a band that
// sees one part of the triangle starts two limits.
template <bool WithEdges, bool PairOnRight, class SpanSink>
void rowsAroundMiddle(const TriangleSetup& t, int x0, int y0, int y1, int64_t width, int64_t row[3], int single,
                      const int pairEdges[2], SpanSink& sink) {
  // The edge of the pair that is not edge k ends at vertex k; the pair's shared vertex is M.
  const int m = 3 - pairEdges[0] - pairEdges[1];
  const bool firstIsLower = t.v[pairEdges[1]].y < t.v[m].y;  // pairEdges[0] joins M and v[pairEdges[1]]
  const int lower = firstIsLower ? pairEdges[0] : pairEdges[1], upper = firstIsLower ? pairEdges[1] : pairEdges[0];
  // Rows up to lastBelow sample below M.
  const int64_t lastBelow = floorDiv(t.v[m].y - kSubpixelHalf - 1, kSubpixelOne);
  EdgeLimit one, pair;
  startLimit(one, t, single, row[single]);
  auto run = [&](int from, int to) {
    if constexpr (PairOnRight) spanRowsOfTwo<WithEdges>(t, x0, from, to, width, row, one, pair, sink);
    else spanRowsOfTwo<WithEdges>(t, x0, from, to, width, row, pair, one, sink);
  };
  int y = y0;
  if (y <= lastBelow) {
    startLimit(pair, t, lower, row[lower]);
    const int to = int(std::min<int64_t>(y1, lastBelow));
    run(y, to);
    y = to + 1;
  }
  if (y > y1) return;
  startLimit(pair, t, upper, t.edgeAt(upper, x0, y) + t.bias[upper]);
  run(y, y1);
}

template <bool WithEdges, class SpanSink>
void spans(const TriangleSetup& t, const Rect& region, SpanSink& sink) {
  const int x0 = std::max(t.minX, region.x), x1 = std::min(t.maxX, region.x + region.width - 1);
  const int y0 = std::max(t.minY, region.y), y1 = std::min(t.maxY, region.y + region.height - 1);
  if (x0 > x1 || y0 > y1) return;
  const int64_t width = x1 - x0;
  int64_t row[3];
  int leftEdges[3], rightEdges[3], flat[3];  // flat: horizontal edges (stepX = 0), covered while E >= 0
  int lefts = 0, rights = 0, flats = 0;
  for (int i = 0; i < 3; ++i) {
    row[i] = t.edgeAt(i, x0, y0) + t.bias[i];
    const int64_t s = t.stepX[i];
    if (s > 0) leftEdges[lefts++] = i;
    else if (s < 0) rightEdges[rights++] = i;
    else flat[flats++] = i;
  }
  // The usual triangle has no horizontal edge: one edge on one side, two on the other.
  if (flats == 0 && lefts == 1 && rights == 2)
    return rowsAroundMiddle<WithEdges, true>(t, x0, y0, y1, width, row, leftEdges[0], rightEdges, sink);
  if (flats == 0 && lefts == 2 && rights == 1)
    return rowsAroundMiddle<WithEdges, false>(t, x0, y0, y1, width, row, rightEdges[0], leftEdges, sink);
  // Slot 0 of each side stands for "no limit" when the triangle has no edge of that side.
  EdgeLimit left[3], right[3];
  for (int k = 0; k < lefts; ++k) startLimit(left[k], t, leftEdges[k], row[leftEdges[k]]);
  for (int k = 0; k < rights; ++k) startLimit(right[k], t, rightEdges[k], row[rightEdges[k]]);
  if (lefts == 0) left[0].start(0, 0, 1);        // lo = 0 on every row
  if (rights == 0) right[0].start(width, 0, 1);  // hi = width on every row
  spanRows<WithEdges>(t, x0, y0, y1, width, row, left, std::max(lefts, 1), right, std::max(rights, 1), flat, flats,
                      sink);
}

}  // namespace detail

// The same coverage as rasterizeTriangle, delivered as one interval per row: a triangle is
// convex, so the covered centres of a row are contiguous. The interval's ends are the exact
// solutions of E_i + bias_i >= 0 in integers (EdgeLimit), so every pixel is covered here exactly
// when rasterizeTriangle covers it. Sink: void(int y, int xl, int xr, const int64_t e[3]) with the
// unbiased edge values at (xl, y); rows bottom to top.
template <class SpanSink>
void rasterizeSpans(const TriangleSetup& t, const Rect& region, SpanSink&& sink) {
  detail::spans<true>(t, region, sink);
}

// rasterizeSpans for a sink that needs no edge values: void(int y, int xl, int xr).
template <class SpanSink>
void rasterizeRowSpans(const TriangleSetup& t, const Rect& region, SpanSink&& sink) {
  detail::spans<false>(t, region, sink);
}

// A third form of the same coverage, for narrow triangles: those whose columns inside the region
// fit in one window of kNarrowColumns. Their rows hold a few pixels each, and solving each row's
// ends (three EdgeLimit steps, then a loop whose length changes from row to row) costs more than
// testing the whole window at once. Lane k of a row is column window + k; it is covered when its
// three biased edge values are >= 0 — rasterizeTriangle's test, exact in integers, so the lanes
// are exactly the pixels rasterizeSpans gives — and its column is inside the triangle's columns
// in the region. The window starts at the triangle's first column, or ends at the buffer's last
// column where the buffer ends sooner.
inline constexpr int kNarrowColumns = 8;
using NarrowLanes = int32_t __attribute__((vector_size(4 * kNarrowColumns)));  // all ones: covered

// Whether rasterizeNarrowRows takes the triangle: its columns in the region fit in a window, and
// the buffer is at least a window wide.
inline bool isNarrow(const TriangleSetup& t, const Rect& region, int bufferWidth) {
  const int x0 = std::max(t.minX, region.x), x1 = std::min(t.maxX, region.x + region.width - 1);
  return x1 - x0 < kNarrowColumns && bufferWidth >= kNarrowColumns;
}

// Sink: void(int y, int window, NarrowLanes covered) for each row with a covered pixel, bottom to
// top. Requires isNarrow(t, region, bufferWidth).
template <class RowSink>
void rasterizeNarrowRows(const TriangleSetup& t, const Rect& region, int bufferWidth, RowSink&& sink) {
  // The edge values in two halves of four 64-bit lanes (GCC lowers a vector of eight lane by lane
  // for AVX2). A lane is covered when its three values are >= 0, that is when their OR is, whose
  // sign is its high 32-bit word's: the eight high words, side by side, are the eight lanes' test.
  using Half = int64_t __attribute__((vector_size(32)));
  using Words = int32_t __attribute__((vector_size(32)));
  static_assert(kNarrowColumns == 8, "two halves of four lanes");
  const int x0 = std::max(t.minX, region.x), x1 = std::min(t.maxX, region.x + region.width - 1);
  const int y0 = std::max(t.minY, region.y), y1 = std::min(t.maxY, region.y + region.height - 1);
  if (x0 > x1 || y0 > y1) return;
  const int window = std::min(x0, bufferWidth - kNarrowColumns);
  const NarrowLanes column = window + NarrowLanes{0, 1, 2, 3, 4, 5, 6, 7};
  const NarrowLanes inColumns = (column >= x0) & (column <= x1);
  Half low[3], high[3];
  for (int i = 0; i < 3; ++i) {
    const int64_t first = t.edgeAt(i, window, y0) + t.bias[i];
    low[i] = first + t.stepX[i] * Half{0, 1, 2, 3};
    high[i] = first + t.stepX[i] * Half{4, 5, 6, 7};
  }
  constexpr int h = std::endian::native == std::endian::little ? 1 : 0;  // a 64-bit lane's high word
  for (int y = y0; y <= y1; ++y) {
    const Words a = std::bit_cast<Words>(low[0] | low[1] | low[2]);
    const Words b = std::bit_cast<Words>(high[0] | high[1] | high[2]);
    const NarrowLanes signs = __builtin_shufflevector(a, b, h, 2 + h, 4 + h, 6 + h, 8 + h, 10 + h, 12 + h, 14 + h);
    const NarrowLanes lanes = (signs >= 0) & inColumns;
    uint64_t words[kNarrowColumns / 2];
    std::memcpy(words, &lanes, sizeof words);
    if ((words[0] | words[1] | words[2] | words[3]) != 0) sink(y, window, lanes);
    for (int i = 0; i < 3; ++i) {
      low[i] += t.stepY[i];
      high[i] += t.stepY[i];
    }
  }
}

}  // namespace shadowref
