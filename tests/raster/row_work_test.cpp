// The estimate of each row's work and the bands cut from it (raster/row_work.h), against splits
// worked out by hand: a row costs its pixels in the triangles' boxes plus 8, a triangle 64 more on
// its first row, every row 1 more; band b of n gets n + 1 - b parts of n (n + 3) / 2.
#include <vector>

#include <catch2/catch.hpp>

#include "raster/row_work.h"

using namespace shadowref;

namespace {
const Rect kRegion{0, 0, 100, 64};
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

TEST_CASE("a triangle's rows weigh by its width inside the region, its first row by 64 more", "[raster][bands]") {
  RowWork work;
  work.reset(64);
  // Rows 0 … 15, 100 pixels wide once clamped to the region (it reaches out on both sides):
  // rows 0 … 15 cost 109 each, row 0 64 more, rows 16 … 63 cost 1: 1856 in all.
  work.addTriangle(-50, -3, 180, 15, kRegion);
  std::vector<int> first;
  // Three bands, shares 4, 3 and 2 of 9: the first has its 4/9 (824.9) at row 6 (7 * 109 + 64 =
  // 827) but a band has at least 16 rows; the second has its 7/9 at row 15 already and ends after
  // 16 rows.
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
  work.addTriangle(120, 0, 130, 63, kRegion);  // right of the region
  work.addTriangle(0, 0, 99, 63, Rect{0, 0, 0, 64});  // an empty region
  work.addClear(Rect{0, 0, 0, 64});
  std::vector<int> a, b;
  CHECK(work.split(0, 63, 3, 4, a) == empty.split(0, 63, 3, 4, b));
  CHECK(a == b);
}

TEST_CASE("counts of groups of triangles add up to the count of all of them", "[raster][bands]") {
  // assembleQueued counts each group's triangles on its own thread and the flush adds them.
  struct Box {
    int minX, minY, maxX, maxY;
  };
  const std::vector<Box> boxes{{0, 0, 99, 5}, {10, 20, 30, 60}, {-5, 40, 200, 45}, {50, 7, 51, 7}, {3, 30, 90, 63}};
  RowWork all, groupA, groupB;
  for (RowWork* w : {&all, &groupA, &groupB}) w->reset(64);
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    all.addTriangle(b.minX, b.minY, b.maxX, b.maxY, kRegion);
    (i % 2 ? groupA : groupB).addTriangle(b.minX, b.minY, b.maxX, b.maxY, kRegion);
  }
  all.addClear(Rect{0, 8, 100, 20});
  groupB.addClear(Rect{0, 8, 100, 20});
  groupA.add(groupB);
  for (int bands : {2, 3, 6}) {
    std::vector<int> a, b;
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
  other.addTriangle(10, 40, 60, 63, kRegion);
  reused.reset(64);
  reused.addTriangle(0, 0, 99, 20, kRegion);
  reused.addClear(Rect{0, 30, 100, 10});
  reused.add(other);
  std::vector<int> a, b;
  REQUIRE(reused.split(0, 63, 3, 4, a) == 3);
  REQUIRE(a != std::vector<int>({0, 1, 2, 3}));
  reused.reset(64);
  fresh.addTriangle(5, 8, 50, 30, kRegion);
  reused.addTriangle(5, 8, 50, 30, kRegion);
  CHECK(fresh.split(0, 63, 3, 4, a) == reused.split(0, 63, 3, 4, b));
  CHECK(a == b);
  // Another height: a new list.
  RowWork taller;
  taller.reset(128);
  reused.reset(128);
  taller.addTriangle(5, 100, 50, 120, Rect{0, 0, 100, 128});
  reused.addTriangle(5, 100, 50, 120, Rect{0, 0, 100, 128});
  CHECK(taller.split(0, 127, 3, 4, a) == reused.split(0, 127, 3, 4, b));
  CHECK(a == b);
}
