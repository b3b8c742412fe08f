// The estimate of each row's work and the bands cut from it (exec/row_work.h), against weights
// and splits worked out by hand: a row costs the pixels a triangle covers in it (a short
// triangle: half its box's width; a tall one: its shape, widest at its middle vertex's row) plus
// 8, a triangle 64 more on its first row, every row 1 more — in 1/256 of a pixel; band b of n gets
// n + 1 - b parts of n (n + 3) / 2.
#include <algorithm>
#include <cstdint>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/row_work.h"
#include "gl/fragment_shader.h"
#include "gl/lighting.h"

using namespace shadowref;

namespace {
const Rect kRegion{0, 0, 100, 64};
const ConstantColorShader constantShader({1.0, 0.5, 0.25, 1.0});
const ColorVaryingShader colorShader;
const GouraudShader gouraudShader;
const PerPixelLightingShader perPixelShader(LightingSetup{});

SetupBounds box(int minX, int minY, int maxX, int maxY) { return {minX, minY, maxX, maxY}; }

// What the estimate reads of a tall triangle's setup: its vertices' rows (the middle one's row is
// its widest: here all three sit on that row's centre) and its area.
TriangleSetup shape(int peakY, int64_t pixels) {
  TriangleSetup t;
  for (WindowVertex& v : t.v) v.y = int64_t(peakY) * kSubpixelOne + kSubpixelHalf;
  t.area2 = pixels << (2 * kSubpixelBits + 1);
  return t;
}
const TriangleSetup kShort = shape(0, 1);  // a short triangle's setup is not read

StencilFaceState test(CompareFunc func, int ref, uint8_t mask) {
  StencilFaceState s;
  s.func = func;
  s.ref = ref;
  s.mask = mask;
  return s;
}
}

TEST_CASE("rows without triangles are cut into shrinking shares of equal rows", "[raster][bands]") {
  RowWork work;
  work.reset(64);
  std::vector<int> first;
  // Two bands: the first takes 3 of 5 parts of 64 rows, so it ends at the first row r with
  // 5 (r + 1) >= 3 * 64: r + 1 = 39.
  CHECK(work.split(0, 63, 2, 16, first) == 2);
  CHECK(first == std::vector<int>{0, 39, 64});
  // Rows 10 … 41 alone (32 rows): 3/5 of 32 is 19.2, so 20 rows.
  CHECK(work.split(10, 41, 2, 16, first) == 1);
  CHECK(first == std::vector<int>{10, 42});  // one band: a second would have 12 rows, under 16
  CHECK(work.split(10, 41, 2, 8, first) == 2);
  CHECK(first == std::vector<int>{10, 30, 42});
}

TEST_CASE("rows without triangles are cut into equal shares when asked", "[raster][bands]") {
  RowWork work;
  work.reset(64);
  std::vector<int> first;
  // Every row weighs 1 pixel: four bands of 16 rows; three of 64 rows end where 3 (r + 1) >= 64
  // and >= 128: r + 1 = 22, 43.
  using Shares = RowWork::Shares;
  CHECK(work.split(0, 63, 4, 8, first, Shares::Equal) == 4);
  CHECK(first == std::vector<int>{0, 16, 32, 48, 64});
  CHECK(work.split(0, 63, 3, 8, first, Shares::Equal) == 3);
  CHECK(first == std::vector<int>{0, 22, 43, 64});
  CHECK(work.split(0, 63, 3, 8, first, Shares::Shrinking) == 3);  // 4, 3 and 2 parts of 9: 28.4, 49.8
  CHECK(first == std::vector<int>{0, 29, 50, 64});
}

TEST_CASE("a short triangle's rows weigh by half its box's width inside the region, its first row by 64 more",
          "[raster][bands]") {
  RowWork work;
  work.reset(64);
  // Rows 0 … 15 in the region (19 rows: short), its box 100 pixels wide once clamped to the
  // region (it reaches out on both sides), half of it 50: rows 0 … 15 cost 50 + 8 + 1 = 59 each,
  // row 0 64 more, rows 16 … 63 cost 1: 1056 in all.
  work.addTriangle(box(-50, -3, 180, 15), kShort, kRegion, true);
  const std::vector<int64_t> weights = work.rowWeights(0, 63);
  CHECK(weights.at(0) == 123 * 256);
  CHECK(weights.at(5) == 59 * 256);
  CHECK(weights.at(15) == 59 * 256);
  CHECK(weights.at(16) == 256);
  std::vector<int> first;
  // Three bands, shares 4, 3 and 2 of 9: the first has its 4/9 (469.3) at row 6 (7 * 59 + 64 =
  // 477) but a band has at least 16 rows; the second has its 7/9 (821.3) at row 15 already and
  // ends after 16 rows.
  CHECK(work.split(0, 63, 3, 16, first) == 3);
  CHECK(first == std::vector<int>{0, 16, 32, 64});
  // Without the 16-row floor the first band ends at row 6.
  CHECK(work.split(0, 63, 3, 1, first) == 3);
  CHECK(first.at(1) == 7);
}

TEST_CASE("triangles and clears outside the region count nothing", "[raster][bands]") {
  RowWork empty, work;
  empty.reset(64);
  work.reset(64);
  work.addTriangle(box(120, 0, 130, 63), kShort, kRegion, true);  // right of the region
  work.addTriangle(box(0, 0, 99, 63), kShort, Rect{0, 0, 0, 64}, true);  // an empty region
  work.addTriangle({120, 0, 130, 63}, shape(10, 300), kRegion, true);  // a tall one right of the region
  work.addClear(Rect{0, 0, 0, 64});
  std::vector<int> a, b;
  CHECK(work.split(0, 63, 3, 4, a) == empty.split(0, 63, 3, 4, b));
  CHECK(a == b);
}

TEST_CASE("counts of groups of triangles add up to the count of all of them", "[raster][bands]") {
  // assembleQueued counts each group's triangles on its own thread and the flush adds them.
  // Short ones and tall ones (41 and 34 rows), one reaching out of the region.
  const std::vector<SetupBounds> triangles{box(0, 0, 99, 5), {10, 20, 30, 60}, box(-5, 40, 200, 45), box(50, 7, 51, 7),
                                           {3, 30, 190, 63}};
  const std::vector<TriangleSetup> setups{kShort, shape(50, 400), kShort, kShort, shape(31, 2500)};
  RowWork all, groupA, groupB;
  for (RowWork* w : {&all, &groupA, &groupB}) w->reset(64);
  for (size_t i = 0; i < triangles.size(); ++i) {
    all.addTriangle(triangles[i], setups[i], kRegion, true);
    (i % 2 ? groupA : groupB).addTriangle(triangles[i], setups[i], kRegion, true);
  }
  all.addClear(Rect{0, 8, 100, 20});
  groupB.addClear(Rect{0, 8, 100, 20});
  groupA.add(groupB);
  for (int bands : {2, 3, 6}) {
    std::vector<int> a, b;
    CHECK(all.rowWeights(0, 63) == groupA.rowWeights(0, 63));
    CHECK(all.split(0, 63, bands, 4, a) == groupA.split(0, 63, bands, 4, b));
    CHECK(a == b);
    CHECK(a.size() >= 3);
  }
}

TEST_CASE("a reset count forgets every triangle, clear and added count, over the same rows or others",
          "[raster][bands]") {
  // reset zeroes only the entries written since the last one: a count reset after triangles,
  // clears and another's count must split as a new one does.
  RowWork fresh, reused, other;
  fresh.reset(64);
  other.reset(64);
  other.addTriangle(box(10, 40, 60, 63), kShort, kRegion, true);
  reused.reset(64);
  reused.addTriangle(box(0, 0, 99, 20), kShort, kRegion, true);
  reused.addTriangle({0, 0, 99, 40}, shape(30, 1500), kRegion, true);  // tall: its ramps must be forgotten too
  reused.addClear(Rect{0, 30, 100, 10});
  reused.add(other);
  std::vector<int> a, b;
  REQUIRE(reused.split(0, 63, 3, 4, a) == 3);
  REQUIRE(a != std::vector<int>({0, 1, 2, 3}));
  reused.reset(64);
  fresh.addTriangle(box(5, 8, 50, 30), kShort, kRegion, true);
  reused.addTriangle(box(5, 8, 50, 30), kShort, kRegion, true);
  CHECK(fresh.rowWeights(0, 63) == reused.rowWeights(0, 63));
  CHECK(fresh.split(0, 63, 3, 4, a) == reused.split(0, 63, 3, 4, b));
  CHECK(a == b);
  // Another height: a new list.
  RowWork taller;
  taller.reset(128);
  reused.reset(128);
  taller.addTriangle(box(5, 100, 50, 120), kShort, Rect{0, 0, 100, 128}, true);
  reused.addTriangle(box(5, 100, 50, 120), kShort, Rect{0, 0, 100, 128}, true);
  CHECK(taller.split(0, 127, 3, 4, a) == reused.split(0, 127, 3, 4, b));
  CHECK(a == b);
}

TEST_CASE("a tall triangle's rows weigh by its shape: rising to its middle vertex's row, then falling", "[raster][bands]") {
  // Rows 0 … 39 (40: tall), middle vertex on row 9, 1000 pixels: 2 × 1000 / 40 = 50 pixels at
  // the peak (12800 in 1/256). Rising over 10 rows by 12800 / 10 = 1280 a row: row k weighs
  // 1280 (k + 1) up to 12800 on row 9. Falling over the 30 rows after it by 12800 / 31 = 412 (cut
  // to an integer) a row: row 10 weighs 412 × 30 = 12360, row 39 412. Each row 8 × 256 + 256 =
  // 2304 more, row 0 64 × 256 = 16384 more.
  const SetupBounds t{0, 0, 99, 39};
  const TriangleSetup s = shape(9, 1000);
  RowWork work;
  work.reset(64);
  work.addTriangle(t, s, kRegion, true);
  std::vector<int64_t> w = work.rowWeights(0, 63);
  CHECK(w.at(0) == 1280 + 2304 + 16384);
  CHECK(w.at(4) == 1280 * 5 + 2304);
  CHECK(w.at(9) == 12800 + 2304);
  CHECK(w.at(10) == 12360 + 2304);
  CHECK(w.at(20) == 412 * 20 + 2304);
  CHECK(w.at(39) == 412 + 2304);
  CHECK(w.at(40) == 256);
  CHECK(w.at(63) == 256);

  // In a region 30 pixels wide (7680) the rows wider than it weigh 7680: rising, rows 0 … 4
  // (1280 × 5 = 6400 < 7680), then rows 5 … 9 at 7680; falling, 412 × 18 = 7416 < 7680, so rows
  // 22 … 39 fall from 7416 to 412 and rows 10 … 21 stay at 7680.
  RowWork narrow;
  narrow.reset(64);
  narrow.addTriangle(t, s, Rect{0, 0, 30, 64}, true);
  w = narrow.rowWeights(0, 63);
  CHECK(w.at(4) == 6400 + 2304);
  CHECK(w.at(5) == 7680 + 2304);
  CHECK(w.at(9) == 7680 + 2304);
  CHECK(w.at(10) == 7680 + 2304);
  CHECK(w.at(21) == 7680 + 2304);
  CHECK(w.at(22) == 7416 + 2304);
  CHECK(w.at(39) == 412 + 2304);

  // In rows 20 … 63 only: its first row there is row 20 (12360 - 412 × 10 = 8240, and the
  // triangle's 64 pixels), and nothing of it is left after row 39.
  RowWork upper;
  upper.reset(64);
  upper.addTriangle(t, s, Rect{0, 20, 100, 44}, true);
  w = upper.rowWeights(20, 63);
  CHECK(w.at(0) == 8240 + 2304 + 16384);
  CHECK(w.at(19) == 412 + 2304);
  CHECK(w.at(20) == 256);
}

TEST_CASE("bands follow a tall triangle's shape, not its box", "[raster][bands]") {
  // Rows 0 … 63, widest on its first row (100 pixels: 2 × 3200 / 64), then narrowing by 25600 /
  // 64 = 400 a row: row y ≥ 1 weighs 400 (64 - y) + 2304, row 0 25600 + 2304 + 16384 = 44288; all
  // rows 995840. Two bands: the first takes 3 of 5 parts, 597504, reached after row 25 (611888;
  // after row 24 593984). By its box the rows would weigh alike and the cut fall after row 38.
  RowWork work;
  work.reset(64);
  work.addTriangle({0, 0, 99, 63}, shape(0, 3200), kRegion, true);
  const std::vector<int64_t> w = work.rowWeights(0, 63);
  int64_t total = 0;
  for (int64_t x : w) total += x;
  CHECK(total == 995840);
  std::vector<int> first;
  CHECK(work.split(0, 63, 2, 4, first) == 2);
  CHECK(first == std::vector<int>{0, 26, 64});
}

TEST_CASE("without shapes every triangle weighs its box's width on every row", "[raster][bands]") {
  // A flush of many setups (RowWork::weighsShapes) leaves the shapes out: rows 0 … 39 of the tall
  // triangle weigh its box's 100 pixels, plus 8, plus 1, row 0 64 more; the short one (rows 50 …
  // 59, 10 pixels wide in the region) 10 + 8 + 1.
  RowWork work;
  work.reset(64);
  work.addTriangle({0, 0, 99, 39}, shape(9, 1000), kRegion, false);
  work.addTriangle(box(-10, 50, 9, 59), kShort, kRegion, false);
  const std::vector<int64_t> w = work.rowWeights(0, 63);
  CHECK(w.at(0) == (100 + 8 + 64 + 1) * 256);
  CHECK(w.at(9) == (100 + 8 + 1) * 256);
  CHECK(w.at(39) == (100 + 8 + 1) * 256);
  CHECK(w.at(40) == 256);
  CHECK(w.at(50) == (10 + 8 + 64 + 1) * 256);
  CHECK(w.at(59) == (10 + 8 + 1) * 256);
  CHECK(RowWork::weighsShapes(382));
  CHECK_FALSE(RowWork::weighsShapes(27000));
}

TEST_CASE("a draw's fragment work weighs its pixels, not its rows' and triangles' fixed costs", "[raster][bands]") {
  // The short triangle of the test above, its fragments three plain ones' (12 quarters): rows
  // 0 … 15 cost 50 × 3 + 8 + 1 = 159 pixels each, row 0 64 more, the rows above 1.
  RowWork work;
  work.reset(64);
  work.addTriangle(box(-50, -3, 180, 15), kShort, kRegion, true, 12);
  std::vector<int64_t> w = work.rowWeights(0, 63);
  CHECK(w.at(0) == 223 * 256);
  CHECK(w.at(15) == 159 * 256);
  CHECK(w.at(16) == 256);
  // The tall triangle of "a tall triangle's rows weigh by its shape", its fragments twice plain
  // ones' (8 quarters): its peak 2 × 12800 = 25600, rising by 2560 a row to row 9, falling by
  // 25600 / 31 = 825 (cut to an integer) a row after it; the fixed costs as before.
  work.reset(64);
  work.addTriangle({0, 0, 99, 39}, shape(9, 1000), kRegion, true, 8);
  w = work.rowWeights(0, 63);
  CHECK(w.at(0) == 2560 + 2304 + 16384);
  CHECK(w.at(9) == 25600 + 2304);
  CHECK(w.at(10) == 825 * 30 + 2304);
  CHECK(w.at(39) == 825 + 2304);
  CHECK(w.at(40) == 256);
}

TEST_CASE("rows of costlier fragments get fewer of a band's rows", "[raster][bands]") {
  // Two boxes weighed by their width (no shapes), rows 0 … 31 and 32 … 63, 100 pixels wide:
  // plain rows cost 100 + 8 + 1 = 109, rows of fragments three times as costly 300 + 8 + 1 = 309,
  // each box's first row 64 more. Two bands, the first taking 3 of 5 parts.
  auto firstBandEnd = [](int upperWork) {
    RowWork work;
    work.reset(64);
    work.addTriangle(box(0, 0, 99, 31), kShort, kRegion, false, kPlainFragmentWork);
    work.addTriangle(box(0, 32, 99, 63), kShort, kRegion, false, upperWork);
    std::vector<int> first;
    REQUIRE(work.split(0, 63, 2, 4, first) == 2);
    return first.at(1);
  };
  // Alike: 7104 in all, 3/5 of it 4262.4; rows 0 … 31 are 3552, row 32 173, then 109 a row:
  // reached after row 37 (4270), so the second band starts at row 38.
  CHECK(firstBandEnd(kPlainFragmentWork) == 38);
  // Upper fragments three times as costly: 13504 in all, 3/5 of it 8102.4; rows 0 … 32 are
  // 3552 + 373, then 309 a row: reached after row 46 (8251).
  CHECK(firstBandEnd(3 * kPlainFragmentWork) == 47);
}

TEST_CASE("a shader's fragments weigh by what the shader interface tells of them", "[raster][bands]") {
  // No colour, a constant one, or at most four varyings (a colour interpolated): a plain fragment.
  // More varyings (position and normal, lit per fragment): three plain ones.
  CHECK(fragmentWorkOf(nullptr) == kPlainFragmentWork);
  CHECK(fragmentWorkOf(&constantShader) == kPlainFragmentWork);
  CHECK(fragmentWorkOf(&colorShader) == kPlainFragmentWork);
  CHECK(fragmentWorkOf(&gouraudShader) == kPlainFragmentWork);
  CHECK(fragmentWorkOf(&perPixelShader) == 3 * kPlainFragmentWork);
}

TEST_CASE("rows whose pixels a stencil test stops weigh down to a quarter", "[raster][bands]") {
  // A lit pass of shadow volumes draws where the stencil equals 0. Stencil of 100 × 64: rows
  // 0 … 15 all 0, rows 16 … 23 half 0, rows 24 … 63 all 1. One box over every row, 100 wide
  // (109 a row, row 0 64 more). Every 8th row is sampled: rows 0 and 8 pass whole (16/16), row 16
  // half (4 + 12 × 50/100 = 10/16), rows 24 … 56 none (4/16).
  std::vector<uint8_t> stencil(100 * 64, 1);
  std::fill_n(stencil.begin(), 100 * 16, uint8_t(0));
  std::fill_n(stencil.begin() + 100 * 16, 50, uint8_t(0));
  RowWork work;
  work.reset(64);
  work.addTriangle(box(0, 0, 99, 63), kShort, kRegion, false);
  work.weighByStencil(stencil.data(), 100, 0, 63, test(CompareFunc::Equal, 0, 0xFF));
  std::vector<int64_t> w = work.rowWeights(0, 63);
  CHECK(w.at(0) == 173 * 256);
  CHECK(w.at(15) == 109 * 256);
  CHECK(w.at(16) == 109 * 256 * 10 / 16);
  CHECK(w.at(23) == 109 * 256 * 10 / 16);
  CHECK(w.at(24) == 109 * 256 / 4);
  CHECK(w.at(63) == 109 * 256 / 4);
  // "Not equal to 0" passes where "equal" stops; a mask of 0xFE makes 1 read as 0.
  work.weighByStencil(stencil.data(), 100, 0, 63, test(CompareFunc::NotEqual, 0, 0xFF));
  w = work.rowWeights(0, 63);
  CHECK(w.at(15) == 109 * 256 / 4);
  CHECK(w.at(63) == 109 * 256);
  work.weighByStencil(stencil.data(), 100, 0, 63, test(CompareFunc::Equal, 0, 0xFE));
  CHECK(work.rowWeights(0, 63).at(63) == 109 * 256);
  // Sampled from the flush's first row: rows 20 … 63 sample rows 20, 28, …, and row 20 is all 1
  // (row 16, half 0, is not read).
  work.weighByStencil(stencil.data(), 100, 20, 63, test(CompareFunc::Equal, 0, 0xFF));
  w = work.rowWeights(20, 63);
  CHECK(w.at(0) == 109 * 256 / 4);
  // A reset count weighs every row whole again.
  work.reset(64);
  work.addTriangle(box(0, 0, 99, 63), kShort, kRegion, false);
  CHECK(work.rowWeights(0, 63).at(63) == 109 * 256);
}

TEST_CASE("rows weigh by the pixels that pass any stencil compare function, with its reference and mask",
          "[raster][bands]") {
  // Stencil of 100 × 8, one sampled row (row 0): values 0 … 99, one a pixel. A box over the rows
  // weighs 109 a row whole (row 0 64 more: 173); a row weighs (4 + 12 × passing / 100) / 16 of it.
  std::vector<uint8_t> stencil(100 * 8);
  for (size_t i = 0; i < stencil.size(); ++i) stencil[i] = uint8_t(i % 100);
  auto firstRow = [&](const StencilFaceState& s) {
    RowWork work;
    work.reset(8);
    work.addTriangle(box(0, 0, 99, 7), kShort, kRegion, false);
    work.weighByStencil(stencil.data(), 100, 0, 7, s);
    return work.rowWeights(0, 7).at(0);
  };
  auto weighs = [](int64_t passing) { return 173 * 256 * (4 + 12 * passing / 100) / 16; };
  // "ref op stored": less than 40 passes where the value is over 40 (59 of them), greater where
  // it is under (40), less-or-equal 60, greater-or-equal 41, equal 1, never none.
  CHECK(firstRow(test(CompareFunc::Less, 40, 0xFF)) == weighs(59));
  CHECK(firstRow(test(CompareFunc::Greater, 40, 0xFF)) == weighs(40));
  CHECK(firstRow(test(CompareFunc::LEqual, 40, 0xFF)) == weighs(60));
  CHECK(firstRow(test(CompareFunc::GEqual, 40, 0xFF)) == weighs(41));
  CHECK(firstRow(test(CompareFunc::Equal, 40, 0xFF)) == weighs(1));
  CHECK(firstRow(test(CompareFunc::Never, 40, 0xFF)) == weighs(0));
  // Mask 0x0F: each value is its low four bits, the reference 40 reads 8. Among 0 … 99 the low
  // bits are under 8 in 52 values (0 … 7 of each sixteen: 6 × 8 + 96 … 99), 8 in 6 (8, 24, …, 88).
  CHECK(firstRow(test(CompareFunc::Greater, 40, 0x0F)) == weighs(52));
  CHECK(firstRow(test(CompareFunc::Equal, 40, 0x0F)) == weighs(6));
  CHECK(firstRow(test(CompareFunc::Less, 40, 0x0F)) == weighs(100 - 52 - 6));
  // A reference beyond 255 is clamped to 255, as GL does: "equal" passes nowhere, "greater"
  // everywhere (every value is below it).
  CHECK(firstRow(test(CompareFunc::Equal, 300, 0xFF)) == weighs(0));
  CHECK(firstRow(test(CompareFunc::Greater, 300, 0xFF)) == weighs(100));
}
