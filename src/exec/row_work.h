// The work a flush's rows are expected to take, and their split into bands of rows for the
// threads (Renderer::flush). Only the split depends on it: every split gives the same bytes, so the
// estimate is free to be rough; it must be cheap, because it looks at every pending triangle.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "gl/fragment_shader.h"
#include "gl/render_state.h"
#include "gl/triangle_setup.h"

namespace shadowref {

// What a fragment that passes its tests costs, in quarters of a plain one's (interpolating a few
// varyings or none, a colour written): the unit of the rows' work per fragment.
inline constexpr int kPlainFragmentWork = 4;

// What shading a fragment of `shader` costs (nullptr: no colour written), estimated from what the
// shader interface tells of it: a constant colour, or a few varyings (a colour interpolated), a
// plain fragment; more (a position and a normal: lighting, shadow-map lookups per fragment) three.
// The estimate compares the draws of one flush — a lit surface costs a fragment markedly more than
// an interpolated colour, and weighed alike the band of its rows would get more than its share.
// Rough by design: any split of rows gives the same bytes.
int fragmentWorkOf(const FragmentShader* shader);

class RowWork {
 public:
  // Forgets every triangle and clear, for a framebuffer of `rows` rows: zeroes what was written
  // (a flush resets a list per assembly task, of 2049 entries for a 2048² map).
  void reset(int rows) {
    if (diff_.size() != size_t(rows) + 1) {
      diff_.assign(size_t(rows) + 1, 0);
      slope_.assign(size_t(rows) + 1, 0);
    } else if (lowest_ <= highest_) {
      std::fill(diff_.begin() + std::ptrdiff_t(lowest_), diff_.begin() + std::ptrdiff_t(highest_) + 1, 0);
      std::fill(slope_.begin() + std::ptrdiff_t(lowest_), slope_.begin() + std::ptrdiff_t(highest_) + 1, 0);
    }
    lowest_ = diff_.size();
    highest_ = 0;
    stencilScale_.clear();
  }

  // A triangle drawn inside `region`: on each of its rows the pixels it covers there, each of
  // fragmentWork quarters of a plain pixel (fragmentWorkOf its draw's shader), and
  // a row's fixed cost, once its fixed cost. Difference lists (each triangle writes a few entries,
  // not one per row), so that a group of triangles on one thread can be counted on its own and
  // added to the others (add). With byShape, a triangle of kShapedRows rows or more weighs each row
  // by its shape — widest at its middle vertex's row, narrowing linearly to its top and bottom
  // rows — cut to the region's width, and a shorter one by half its box's width in the region (its
  // rows' mean, about); without, every triangle weighs each row by its box's width in the region.
  // The setup is read only for a triangle weighed by its shape (its vertices' rows and its area).
  void addTriangle(const SetupBounds& t, const TriangleSetup& setup, const Rect& region, bool byShape,
                   int fragmentWork = kPlainFragmentWork) {
    const int top = std::min(t.maxY, region.y + region.height - 1), bottom = std::max(t.minY, region.y);
    const int64_t width = int64_t(std::min(t.maxX, region.x + region.width - 1)) - std::max(t.minX, region.x) + 1;
    if (bottom > top || width <= 0) return;
    const bool shaped = byShape && t.maxY - t.minY + 1 >= kShapedRows;
    const int64_t pixel = pixelUnits(fragmentWork);
    const int64_t row = (shaped ? 0 : byShape ? (width + 1) >> 1 : width) * pixel + kRowCost * kUnit;
    diff_[size_t(bottom)] += row + kTriangleCost * kUnit;
    diff_[size_t(bottom) + 1] -= kTriangleCost * kUnit;
    diff_[size_t(top) + 1] -= row;
    touched(size_t(bottom), size_t(top) + 1);
    if (shaped) addShape(t, setup, bottom, top, width, pixel);
  }
  // Whether a flush of this many setups is weighed by the triangles' shapes: a pass of many small
  // triangles (tens of thousands) evens out what their boxes get wrong, and weighing their
  // shapes would cost it more than its bands gain; a pass of a few hundred large ones (walls and
  // volume sides) is where a box gives a band the wrong share.
  static bool weighsShapes(size_t setups) { return setups <= 4096; }
  // A cleared rectangle: a cleared row costs about a quarter of a drawn one.
  void addClear(const Rect& region);
  // A flush whose every draw passes the same stencil test and writes no stencil (the lit passes of
  // shadow volumes: "equal to 0"): each row weighs by the share of its pixels that pass, from a
  // quarter (none pass: the fragments stop at the test) to all of it. Measured on every
  // kStencilSampleRows-th row from rows [minY, maxY] of the stencil buffer (`width` bytes a row),
  // with the test's own compare function, reference and mask. Until reset.
  void weighByStencil(const uint8_t* stencil, int width, int minY, int maxY, const StencilFaceState& test);
  static constexpr int kStencilSampleRows = 8;
  // Another count over the same rows (only the entries it wrote: with many threads a flush adds
  // many groups' lists, each over a few of the rows).
  void add(const RowWork& other);

  // Cuts rows [minY, maxY] into at most maxBands bands, each at least minRows rows (unless all of
  // them are fewer): fills firstRow (band b is rows [firstRow[b], firstRow[b + 1])), returns the
  // count. The threads take the bands in order, so the bands get shrinking shares of the estimated
  // work — maxBands + 1, maxBands, … 2 parts — and the last ones, small, even out the threads'
  // ends. The city's shadow volumes crowd into the lower rows: equal rows would leave one thread
  // most of them.
  int split(int minY, int maxY, int maxBands, int minRows, std::vector<int>& firstRow) {
    return split(minY, maxY, maxBands, minRows, firstRow, Shares::Shrinking);
  }
  // The same with every band an equal share (Shares::Equal): bands that other threads help to
  // finish (Renderer::countByBands) need no small ones at the end.
  enum class Shares { Shrinking, Equal };
  int split(int minY, int maxY, int maxBands, int minRows, std::vector<int>& firstRow, Shares shares);
  // Rows [minY, maxY]'s estimated work, in 1/kUnit of a pixel (what split cuts).
  std::vector<int64_t> rowWeights(int minY, int maxY) const;
  static constexpr int64_t kUnit = 256;

 private:
  // A row's and a triangle's fixed costs, in pixels (the lists count in 1/kUnit of a pixel: a tall
  // sliver's width changes by less than a pixel a row).
  static constexpr int64_t kRowCost = 8, kTriangleCost = 64;
  // The height from which a triangle's rows are weighed by its shape.
  static constexpr int kShapedRows = 32;
  // A pixel of fragmentWork quarters of a plain one, in 1/kUnit of a plain pixel; the work kept
  // between 1 and 128 quarters, so that a tall triangle's ramps stay far from overflowing.
  static int64_t pixelUnits(int fragmentWork) {
    return kUnit / kPlainFragmentWork * std::clamp(fragmentWork, 1, 128);
  }
  // The pixels of a tall triangle's rows [bottom, top] (inside the region), at most `width` a row,
  // each `pixel` (pixelUnits) in the lists.
  void addShape(const SetupBounds& t, const TriangleSetup& setup, int bottom, int top, int64_t width, int64_t pixel);
  // Rows [first, last] (clipped to [bottom, top]) weighing start, start + step, … (in 1/kUnit).
  void addRamp(int first, int last, int64_t start, int64_t step, int bottom, int top);
  // Fills `work` with rows [minY, maxY]'s work, returns their sum.
  int64_t weigh(int minY, int maxY, std::vector<int64_t>& work) const;
  std::vector<int64_t> diff_;  // per row, what its work adds to the row above's
  std::vector<int64_t> slope_;  // per row, what it adds to the next rows' differences (ramps)
  std::vector<int64_t> work_;  // split's: the work of each of its rows
  // weighByStencil's, in sixteenths, for the rows from stencilFirstRow_ on, kStencilSampleRows a
  // sample; empty: every row whole.
  std::vector<int64_t> stencilScale_;
  int stencilFirstRow_ = 0;
  size_t lowest_ = 0, highest_ = 0;  // the entries of diff_ written since reset: [lowest_, highest_]
  void touched(size_t first, size_t last) {
    lowest_ = std::min(lowest_, first);
    highest_ = std::max(highest_, last);
  }
};

}  // namespace shadowref
