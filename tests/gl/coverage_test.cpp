// Coverage (gl/coverage.h): the top-left rule decided in setup and consumed by covers(), on edges
// through pixel centres, with the expected pixels counted by hand.
#include <catch2/catch.hpp>

#include "gl/coverage.h"
#include "gl/stage_fixtures.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {
int coveredCount(const TriangleSetup& t, const Rect& region) {
  std::vector<CoveredPixel> pixels;
  coveredPixels(t, region, pixels);
  return int(pixels.size());
}
}  // namespace

TEST_CASE("coverage: the diagonal shared by two triangles goes to the one it is a left edge of", "[gl][coverage]") {
  // The 4x4 square cut along its diagonal (0,0)-(4,4), which runs through the centres (i + 1/2,
  // i + 1/2). Lower-right triangle A: the diagonal is its left edge (it runs down, (4,4) -> (0,0),
  // in A's counter-clockwise order), so A takes the four centres on it: the pixels with x >= y,
  // 4 + 3 + 2 + 1 = 10. Upper-left triangle B has it as a right edge: the pixels with x < y, 6.
  const TriangleSetup a = setupOf(windowAt(0, 0), windowAt(4, 0), windowAt(4, 4));
  const TriangleSetup b = setupOf(windowAt(0, 0), windowAt(4, 4), windowAt(0, 4));
  REQUIRE(a.area2 > 0);
  REQUIRE(b.area2 > 0);
  const Rect region{0, 0, 4, 4};
  CHECK(coveredCount(a, region) == 10);
  CHECK(coveredCount(b, region) == 6);
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      int64_t e[3];
      const bool inA = covers(a, x, y, e), inB = covers(b, x, y, e);
      INFO("pixel " << x << ", " << y);
      CHECK(inA == (x >= y));
      CHECK(inA != inB);  // every centre of the square exactly once
    }
  }
}

TEST_CASE("coverage: a horizontal edge through a row of centres is covered by the triangle below it", "[gl][coverage]") {
  // Row 2's centres lie on y = 2.5. Below it, T's edge (4,2.5) -> (0,2.5) runs right to left with
  // the interior below: a top edge, covered. Above it, U's edge (0,2.5) -> (4,2.5) is a bottom
  // edge: not covered. Row 2 is drawn exactly once, by T: its 4 pixels.
  const TriangleSetup t = setupOf(windowAt(2, 0), windowAt(4, 2.5), windowAt(0, 2.5));
  const TriangleSetup u = setupOf(windowAt(0, 2.5), windowAt(4, 2.5), windowAt(2, 5));
  REQUIRE(t.area2 > 0);
  REQUIRE(u.area2 > 0);
  for (int x = 0; x < 4; ++x) {
    int64_t e[3];
    INFO("pixel " << x << ", 2");
    CHECK(covers(t, x, 2, e));
    CHECK_FALSE(covers(u, x, 2, e));
  }
}

TEST_CASE("coverage: the candidates are the setup's bounds cut to the region", "[gl][coverage]") {
  // Bounds of (0,0)-(4,0)-(4,4): centres 0.5 .. 3.5, pixels 0..3 both ways; a region from (2, 1)
  // of 10 x 2 leaves columns 2..3, rows 1..2.
  const TriangleSetup a = setupOf(windowAt(0, 0), windowAt(4, 0), windowAt(4, 4));
  const Rect box = candidatePixels(a, Rect{2, 1, 10, 2});
  CHECK(box.x == 2);
  CHECK(box.y == 1);
  CHECK(box.width == 2);
  CHECK(box.height == 2);
  // Inside it, A covers (2,1), (3,1), (2,2), (3,2): x >= y everywhere there.
  CHECK(coveredCount(a, Rect{2, 1, 10, 2}) == 4);
  CHECK(candidatePixels(a, Rect{5, 0, 3, 3}).width == 0);  // beyond the triangle
}

TEST_CASE("coverage: the edge values handed on are unbiased and sum to twice the area", "[gl][coverage]") {
  const TriangleSetup a = setupOf(windowAt(0, 0), windowAt(4, 0), windowAt(4, 4));
  std::vector<CoveredPixel> pixels;
  coveredPixels(a, Rect{0, 0, 4, 4}, pixels);
  REQUIRE(!pixels.empty());
  for (const CoveredPixel& p : pixels) CHECK(p.e[0] + p.e[1] + p.e[2] == a.area2);
  // On the diagonal (pixel (1,1)) the edge opposite vertex 1 is exactly 0: E is not biased.
  int64_t e[3];
  REQUIRE(covers(a, 1, 1, e));
  CHECK((e[0] == 0 || e[1] == 0 || e[2] == 0));
}
