// Coverage: which pixel centres a triangle owns. Pixel centres are at half-integers; a centre
// exactly on an edge belongs to the triangle when the edge is a left or a top edge (top-left rule,
// y up), so triangles sharing an edge cover each centre on it exactly once (watertight).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/rasterizer.h"
#include "exec/renderer.h"
#include "support/polygon_geometry.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

std::string coverageOf(Framebuffer& fb, const std::vector<ClipVertex>& triangles) {
  const RenderState s = coverageCountingState(fb);
  Renderer r(fb);
  draw(r, s, triangles);
  return stencilPicture(fb);
}

std::vector<ClipVertex> reversed(std::vector<ClipVertex> triangles) {
  for (size_t i = 0; i + 2 < triangles.size(); i += 3) std::swap(triangles[i + 1], triangles[i + 2]);
  return triangles;
}

// xorshift64: the random tests' vertices, the same on every platform.
struct XorShift {
  uint64_t state;
  uint64_t operator()() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
  }
};

}  // namespace

TEST_CASE("a rectangle with corners on pixel centres covers the centres on its left and top edges",
          "[raster][coverage]") {
  // [1.5, 5.5] x [1.5, 4.5]: columns 1..4 (x = 5.5 is the right edge), rows 2..4 (y = 1.5 is the
  // bottom edge, y = 4.5 the top edge); the diagonal is shared and covered once.
  const std::string expected = rows({"........",
                                     "........",
                                     "........",
                                     ".1111...",
                                     ".1111...",
                                     ".1111...",
                                     "........",
                                     "........"});
  {
    Framebuffer fb(8, 8);
    CHECK(coverageOf(fb, windowRect(fullViewportState(fb).viewport, 1.5, 1.5, 5.5, 4.5)) == expected);
  }
  {  // the other diagonal
    Framebuffer fb(8, 8);
    const Viewport vp = fullViewportState(fb).viewport;
    CHECK(coverageOf(fb, windowTriangles(vp, {{1.5, 1.5, 0.5}, {5.5, 1.5, 0.5}, {1.5, 4.5, 0.5},
                                              {5.5, 1.5, 0.5}, {5.5, 4.5, 0.5}, {1.5, 4.5, 0.5}})) == expected);
  }
  {  // clockwise triangles cover the same centres
    Framebuffer fb(8, 8);
    CHECK(coverageOf(fb, reversed(windowRect(fullViewportState(fb).viewport, 1.5, 1.5, 5.5, 4.5))) == expected);
  }
}

TEST_CASE("two rectangles sharing an edge through pixel centres cover it once", "[raster][coverage]") {
  Framebuffer fb(8, 8);
  const Viewport vp = fullViewportState(fb).viewport;
  std::vector<ClipVertex> v = windowRect(vp, 1.5, 1.5, 5.5, 4.5);
  const std::vector<ClipVertex> right = windowRect(vp, 5.5, 1.5, 7.5, 4.5);
  v.insert(v.end(), right.begin(), right.end());
  CHECK(coverageOf(fb, v) == rows({"........",
                                   "........",
                                   "........",
                                   ".111111.",
                                   ".111111.",
                                   ".111111.",
                                   "........",
                                   "........"}));
}

TEST_CASE("top-left rule: a right triangle with edges through pixel centres", "[raster][coverage]") {
  // (0.5, 0.5) (6.5, 0.5) (0.5, 6.5): left edge x = 0.5 in, bottom edge y = 0.5 out, hypotenuse
  // x + y = 7 (a right edge) out. Centres (x + .5, y + .5) with y >= 1 and x + y < 6.
  const std::string lower = rows({"........",
                                  "........",
                                  "1.......",
                                  "11......",
                                  "111.....",
                                  "1111....",
                                  "11111...",
                                  "........"});
  Framebuffer a(8, 8), b(8, 8);
  const Viewport vp = fullViewportState(a).viewport;
  const std::vector<ClipVertex> t = windowTriangles(vp, {{0.5, 0.5, 0.5}, {6.5, 0.5, 0.5}, {0.5, 6.5, 0.5}});
  CHECK(coverageOf(a, t) == lower);
  CHECK(coverageOf(b, reversed(t)) == lower);
  // Its complement (6.5, 0.5) (6.5, 6.5) (0.5, 6.5) owns the hypotenuse (a left edge for it) and the
  // top edge y = 6.5, not the right edge x = 6.5: together they tile columns 0..5, rows 1..6 once.
  Framebuffer c(8, 8);
  std::vector<ClipVertex> both = t;
  const std::vector<ClipVertex> upper = windowTriangles(vp, {{6.5, 0.5, 0.5}, {6.5, 6.5, 0.5}, {0.5, 6.5, 0.5}});
  both.insert(both.end(), upper.begin(), upper.end());
  CHECK(coverageOf(c, both) == rows({"........",
                                     "111111..",
                                     "111111..",
                                     "111111..",
                                     "111111..",
                                     "111111..",
                                     "111111..",
                                     "........"}));
}

TEST_CASE("top-left rule: a triangle with a top edge and two slanted edges through centres", "[raster][coverage]") {
  // (0.5, 6.5) (3.5, 0.5) (6.5, 6.5): the top edge y = 6.5 and the left edge are in, the right edge
  // is out. Row y (centre py = y + .5) holds px >= 0.5 + (6.5 - py) / 2 and px < 3.5 + (py - 0.5) / 2.
  const std::string expected = rows({"........",
                                     "111111..",
                                     ".11111..",
                                     ".1111...",
                                     "..111...",
                                     "..11....",
                                     "...1....",
                                     "........"});
  Framebuffer a(8, 8), b(8, 8);
  const std::vector<ClipVertex> t =
      windowTriangles(fullViewportState(a).viewport, {{0.5, 6.5, 0.5}, {3.5, 0.5, 0.5}, {6.5, 6.5, 0.5}});
  CHECK(coverageOf(a, t) == expected);
  CHECK(coverageOf(b, reversed(t)) == expected);
}

// ---------------------------------------------------------------------------------------------
// Watertightness: meshes counted with INCR must give 1 on every pixel of their union, 0 outside.

namespace {

struct IndexedMesh {
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
  Polygon2 outline;  // window space
};

// Window point -> clip vertex, scaled by a random w so the divide is exercised too.
ClipVertex clipVertexAt(const Viewport& vp, const glm::dvec2& p, TestRandom& rng) {
  ClipVertex v = windowVertex(vp, p.x, p.y, 0.5);
  v.position *= rng.uniform(0.5, 4.0);
  return v;
}

// An n x n jittered grid over [-6, 70]^2 (beyond a 64x64 viewport on every side), each cell split
// along a random diagonal. `a` and `b` wind counter-clockwise before `winding` is applied.
IndexedMesh jitteredGrid(const Viewport& vp, int n, uint64_t seed, Winding winding) {
  TestRandom rng(seed);
  IndexedMesh m;
  const double lo = -6.0, cell = 76.0 / n;
  std::vector<glm::dvec2> points;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      points.push_back({lo + cell * i + rng.uniform(-0.3, 0.3) * cell, lo + cell * j + rng.uniform(-0.3, 0.3) * cell});
  for (const glm::dvec2& p : points) m.vertices.push_back(clipVertexAt(vp, p, rng));
  m.indices = gridTriangles(n, n, winding, rng);
  auto at = [&](int i, int j) { return size_t(j * (n + 1) + i); };
  for (int i = 0; i <= n; ++i) m.outline.push_back(points[at(i, 0)]);
  for (int j = 1; j <= n; ++j) m.outline.push_back(points[at(n, j)]);
  for (int i = n - 1; i >= 0; --i) m.outline.push_back(points[at(i, n)]);
  for (int j = n - 1; j >= 1; --j) m.outline.push_back(points[at(0, j)]);
  return m;
}

// `count` triangles around `centre`, outer vertices at jittered angles and radii in [rMin, rMax].
IndexedMesh fan(const Viewport& vp, const glm::dvec2& centre, int count, double rMin, double rMax, uint64_t seed,
                Winding winding) {
  TestRandom rng(seed);
  IndexedMesh m;
  m.vertices.push_back(clipVertexAt(vp, centre, rng));
  for (int k = 0; k < count; ++k) {
    const double angle = 2.0 * std::numbers::pi * (k + rng.uniform(0.0, 0.8)) / count;
    const double r = rng.uniform(rMin, rMax);
    const glm::dvec2 p = centre + r * glm::dvec2(std::cos(angle), std::sin(angle));
    m.outline.push_back(p);
    m.vertices.push_back(clipVertexAt(vp, p, rng));
  }
  for (int k = 0; k < count; ++k)
    addTriangle(m.indices, 0, uint32_t(1 + k), uint32_t(1 + (k + 1) % count), winding, rng);
  return m;
}

// Draws the mesh with INCR and compares every pixel with the independent union of its outline.
void requireCoveredExactlyOnce(const IndexedMesh& m, int size) {
  Framebuffer fb(size, size);
  const RenderState s = coverageCountingState(fb);
  Renderer r(fb);
  DrawCall call;
  call.state = &s;
  call.vertices = m.vertices;
  call.indices = m.indices;
  r.draw(call);

  requireCoverage(fb, m.outline);
}

const char* windingName(Winding w) { return w == Winding::CCW ? "CCW" : w == Winding::CW ? "CW" : "mixed"; }

}  // namespace

TEST_CASE("watertight: random jittered grid meshes cover their union exactly once", "[raster][watertight]") {
  Framebuffer probe(64, 64);
  const Viewport vp = fullViewportState(probe).viewport;
  for (Winding winding : {Winding::CCW, Winding::CW, Winding::Mixed}) {
    for (uint64_t seed = 1; seed <= 8; ++seed) {
      INFO("winding " << windingName(winding) << ", seed " << seed);
      requireCoveredExactlyOnce(jitteredGrid(vp, 12, seed, winding), 64);
    }
  }
  // A fine grid: cells about one pixel wide, so many vertices share pixels.
  for (uint64_t seed = 100; seed < 103; ++seed) {
    INFO("fine grid, seed " << seed);
    requireCoveredExactlyOnce(jitteredGrid(vp, 70, seed, Winding::Mixed), 64);
  }
}

TEST_CASE("watertight: 64-triangle fans cover their union exactly once, also around a pixel centre",
          "[raster][watertight]") {
  Framebuffer probe(64, 64);
  const Viewport vp = fullViewportState(probe).viewport;
  const glm::dvec2 centres[] = {
      {32.5, 32.5},          // exactly on a pixel centre: all 64 triangles meet there
      {32.0, 32.0},          // on a pixel corner
      {20.5, 41.0},          // on a pixel edge midpoint line
      {31.377, 29.8125},     // arbitrary
      {3.25, 60.6},          // near a corner: much of the fan is outside the viewport
  };
  for (Winding winding : {Winding::CCW, Winding::CW, Winding::Mixed}) {
    uint64_t seed = 7;
    for (const glm::dvec2& c : centres) {
      INFO("winding " << windingName(winding) << ", centre " << c.x << "," << c.y << ", seed " << seed);
      requireCoveredExactlyOnce(fan(vp, c, 64, 10.0, 45.0, seed++, winding), 64);
    }
  }
}

TEST_CASE("row spans cover exactly the pixels whose three edge functions pass, for random triangles",
          "[raster][coverage][spans]") {
  // The oracle is the definition: pixel (x, y) is covered when E_i + bias_i >= 0 for i = 0, 1, 2,
  // each E_i evaluated from scratch at the pixel centre. rasterizeSpans solves those inequalities
  // per row by division; slivers, huge triangles reaching far outside the region and edges through
  // pixel centres (coordinates on the 1/256 grid at half-pixels) are all in the mix.
  const Rect region{3, 2, 61, 57};
  XorShift next{0x9E3779B97F4A7C15ull};
  auto coordinate = [&](int kind) -> int64_t {
    const int64_t r = int64_t(next() % 100000);
    switch (kind) {
      case 0: return (r % 72) * kSubpixelOne + kSubpixelHalf;           // on a pixel centre
      case 1: return r % (72 * kSubpixelOne);                            // anywhere near the region
      default: return (r - 50000) * int64_t(next() % 4000) + 30 * kSubpixelOne;  // far away
    }
  };
  RenderState rs;
  const DepthCodec codec;
  int checked = 0, coveredTotal = 0;
  for (int n = 0; n < 3000; ++n) {
    WindowVertex v[3];
    const int kind = int(next() % 3);
    for (WindowVertex& w : v) {
      w.x = coordinate(kind == 2 && next() % 2 ? 2 : kind);
      w.y = coordinate(kind == 2 && next() % 2 ? 2 : kind);
      w.fx = double(w.x) / kSubpixelOne;
      w.fy = double(w.y) / kSubpixelOne;
    }
    if (n % 7 == 0) v[2].x = v[1].x + (v[1].x - v[0].x) / 97;  // slivers
    TriangleSetup t;
    if (!setupTriangle(v[0], v[1], v[2], FrontFacing, rs, codec, t)) continue;
    std::vector<uint8_t> spans(size_t(region.width * region.height), 0);
    bool edgesRight = true;
    rasterizeSpans(t, region, [&](int y, int xl, int xr, const int64_t* e) {
      for (int i = 0; i < 3; ++i) edgesRight = edgesRight && e[i] == t.edgeAt(i, xl, y);
      for (int x = xl; x <= xr; ++x) ++spans[size_t((y - region.y) * region.width + (x - region.x))];
    });
    int wrong = 0;
    for (int y = region.y; y < region.y + region.height; ++y)
      for (int x = region.x; x < region.x + region.width; ++x) {
        bool inside = true;
        for (int i = 0; i < 3; ++i) inside = inside && t.edgeAt(i, x, y) + t.bias[i] >= 0;
        const uint8_t got = spans[size_t((y - region.y) * region.width + (x - region.x))];
        wrong += got != (inside ? 1 : 0);
        coveredTotal += inside;
      }
    INFO("triangle " << n << ": (" << v[0].x << "," << v[0].y << ") (" << v[1].x << "," << v[1].y << ") (" << v[2].x
                     << "," << v[2].y << ")");
    REQUIRE(wrong == 0);
    REQUIRE(edgesRight);
    ++checked;
  }
  CHECK(checked > 2500);
  CHECK(coveredTotal > 100000);  // the triangles really cover something
}

namespace {

// What rasterizeNarrowRows gave for one triangle, against the oracle: every pixel of the buffer's
// rows [0, rows) inside the region whose three biased edge values are >= 0, and no other.
struct NarrowRowsCheck {
  int wrong = 0, covered = 0;
  bool windowsInside = true, rowsNonEmpty = true, rowsInOrder = true, shiftedWindow = false;
};

NarrowRowsCheck checkNarrowRows(const TriangleSetup& t, const Rect& region, int bufferWidth, int rows) {
  NarrowRowsCheck c;
  std::vector<uint8_t> lanes(size_t(bufferWidth) * size_t(rows), 0);
  int lastRow = -1;
  rasterizeNarrowRows(t, region, bufferWidth, [&](int y, int window, NarrowLanes covered) {
    c.windowsInside = c.windowsInside && window >= 0 && window + kNarrowColumns <= bufferWidth;
    c.shiftedWindow = c.shiftedWindow || window < std::max(t.minX, region.x);
    c.rowsInOrder = c.rowsInOrder && y > lastRow;
    lastRow = y;
    bool any = false;
    for (int k = 0; k < kNarrowColumns; ++k) {
      if (covered[k] == 0) continue;
      any = true;
      REQUIRE(covered[k] == -1);
      ++lanes[size_t(y * bufferWidth + window + k)];
    }
    c.rowsNonEmpty = c.rowsNonEmpty && any;
  });
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < bufferWidth; ++x) {
      bool inside = y >= region.y && y < region.y + region.height && x >= region.x && x < region.x + region.width;
      for (int i = 0; i < 3; ++i) inside = inside && t.edgeAt(i, x, y) + t.bias[i] >= 0;
      c.wrong += lanes[size_t(y * bufferWidth + x)] != (inside ? 1 : 0);
      c.covered += inside;
    }
  return c;
}

}  // namespace

TEST_CASE("narrow rows cover exactly the pixels whose three edge functions pass, in a window inside the buffer",
          "[raster][coverage][narrow]") {
  // The same oracle as the spans' test, for the lane masks of rasterizeNarrowRows: triangles at
  // most a few pixels wide (slivers, edges through pixel centres, points far outside), regions that
  // cut wide triangles down to a few columns, and buffers whose last columns force the window to
  // start left of the triangle.
  TestRandom random(0xD1B54A32D192ED03ull);
  auto next = [&]() { return random.bits(); };
  RenderState rs;
  const DepthCodec codec;
  int checked = 0, coveredTotal = 0, shiftedWindows = 0;
  for (int n = 0; n < 4000; ++n) {
    const int bufferWidth = 8 + int(next() % 40);
    const int left = int(next() % uint64_t(bufferWidth));
    WindowVertex v[3];
    const bool cutByRegion = n % 3 == 0;
    for (WindowVertex& w : v) {
      const int64_t spread = cutByRegion ? 40 * kSubpixelOne : 9 * kSubpixelOne;
      w.x = int64_t(left) * kSubpixelOne + int64_t(next() % uint64_t(spread)) - (cutByRegion ? 20 * kSubpixelOne : 0);
      w.y = int64_t(next() % uint64_t(30 * kSubpixelOne));
      if (n % 5 == 0) {  // on pixel centres
        w.x = (w.x / kSubpixelOne) * kSubpixelOne + kSubpixelHalf;
        w.y = (w.y / kSubpixelOne) * kSubpixelOne + kSubpixelHalf;
      }
      w.fx = double(w.x) / kSubpixelOne;
      w.fy = double(w.y) / kSubpixelOne;
    }
    if (n % 7 == 0) v[2].x = v[1].x + (v[1].x - v[0].x) / 97;  // slivers
    TriangleSetup t;
    if (!setupTriangle(v[0], v[1], v[2], FrontFacing, rs, codec, t)) continue;
    const int regionX = cutByRegion ? std::clamp(left + int(next() % 5) - 2, 0, bufferWidth - 1) : 0;
    const int regionWidth = cutByRegion ? std::min(1 + int(next() % 8), bufferWidth - regionX) : bufferWidth;
    const Rect region{regionX, 1, regionWidth, 27};
    if (!isNarrow(t, region, bufferWidth)) continue;
    const NarrowRowsCheck c = checkNarrowRows(t, region, bufferWidth, 40);
    INFO("triangle " << n << ": (" << v[0].x << "," << v[0].y << ") (" << v[1].x << "," << v[1].y << ") (" << v[2].x
                     << "," << v[2].y << "), buffer width " << bufferWidth << ", region x " << region.x << " width "
                     << region.width);
    REQUIRE(c.wrong == 0);
    REQUIRE(c.windowsInside);
    REQUIRE(c.rowsNonEmpty);
    REQUIRE(c.rowsInOrder);
    coveredTotal += c.covered;
    shiftedWindows += c.shiftedWindow;
    ++checked;
  }
  CHECK(checked > 2000);
  CHECK(coveredTotal > 20000);
  CHECK(shiftedWindows > 50);  // the buffer's right end moved the window often enough to be tested
}

TEST_CASE("narrow rows of triangles reaching far beyond the region, whose edge values need 64 bits",
          "[raster][coverage][narrow]") {
  // A region a few columns wide cuts triangles whose vertices lie up to 2^18 pixels away (inside
  // the guard band): their edge values at the region's pixels reach 2^40 and more, so a test that
  // looked at fewer than 64 bits of them would go wrong here.
  TestRandom random(0x9E3779B97F4A7C15ull);
  auto next = [&]() { return random.bits(); };
  RenderState rs;
  const DepthCodec codec;
  int checked = 0, coveredTotal = 0, largeValues = 0;
  for (int n = 0; n < 1500; ++n) {
    const int bufferWidth = 8 + int(next() % 40);
    const Rect region{int(next() % uint64_t(bufferWidth - 7)), 1, 1 + int(next() % 8), 38};
    const int64_t reach = int64_t(1) << (10 + next() % 9);  // 2^10 … 2^18 pixels
    WindowVertex v[3];
    for (WindowVertex& w : v) {
      w.x = (int64_t(region.x) + int64_t(next() % uint64_t(2 * reach)) - reach) * kSubpixelOne + int64_t(next() % 256);
      w.y = (int64_t(next() % uint64_t(2 * reach)) - reach + 20) * kSubpixelOne + int64_t(next() % 256);
      w.fx = double(w.x) / kSubpixelOne;
      w.fy = double(w.y) / kSubpixelOne;
    }
    TriangleSetup t;
    if (!setupTriangle(v[0], v[1], v[2], FrontFacing, rs, codec, t)) continue;
    if (!isNarrow(t, region, bufferWidth)) continue;
    int64_t largest = 0;
    for (int i = 0; i < 3; ++i) largest = std::max(largest, std::abs(t.edgeAt(i, region.x, region.y) + t.bias[i]));
    largeValues += largest >= (int64_t(1) << 32);
    const NarrowRowsCheck c = checkNarrowRows(t, region, bufferWidth, 40);
    INFO("triangle " << n << ", reach " << reach);
    REQUIRE(c.wrong == 0);
    REQUIRE(c.rowsNonEmpty);
    coveredTotal += c.covered;
    ++checked;
  }
  CHECK(checked > 500);
  CHECK(largeValues > 300);
  CHECK(coveredTotal > 5000);  // many of them cover the region's pixels
}

TEST_CASE("a triangle is narrow when its columns in the region fit in one window of a wide enough buffer",
          "[raster][coverage][narrow]") {
  TriangleSetup t;
  t.minX = 10;
  t.maxX = 17;  // eight columns
  t.minY = 0;
  t.maxY = 5;
  CHECK(isNarrow(t, Rect{0, 0, 64, 64}, 64));
  CHECK_FALSE(isNarrow(t, Rect{0, 0, 64, 64}, 7));  // no window of eight columns in the buffer
  t.maxX = 18;  // nine columns
  CHECK_FALSE(isNarrow(t, Rect{0, 0, 64, 64}, 64));
  CHECK(isNarrow(t, Rect{12, 0, 4, 64}, 64));  // the region leaves four of them
}

namespace {
WindowVertex vertexAt(double x, double y) {
  WindowVertex w;
  w.x = std::llround(x * kSubpixelOne);
  w.y = std::llround(y * kSubpixelOne);
  w.fx = x;
  w.fy = y;
  return w;
}
}  // namespace

TEST_CASE("the columns a triangle may cover in a band of rows hold every pixel it covers there",
          "[raster][coverage][columns]") {
  // The oracle is the edge functions at every pixel centre of the band's rows. Triangles of every
  // kind: small ones, slivers, vertices on pixel centres, and vertices far out in the guard band
  // (a shadow volume's far end) whose edges cross the band's rows at a slant.
  TestRandom random(0x2545F4914F6CDD1Dull);
  auto next = [&]() { return random.bits(); };
  RenderState rs;
  const DepthCodec codec;
  const Rect region{0, 0, 96, 80};
  int checked = 0, coveredTotal = 0, narrowed = 0;
  for (int n = 0; n < 3000; ++n) {
    WindowVertex v[3];
    for (WindowVertex& w : v) {
      const int64_t reach = n % 4 == 0 ? int64_t(1) << (8 + next() % 12) : 100;  // up to 2^19 pixels
      w.x = int64_t(next() % uint64_t(2 * reach * kSubpixelOne)) - (reach - 48) * kSubpixelOne;
      w.y = int64_t(next() % uint64_t(2 * reach * kSubpixelOne)) - (reach - 40) * kSubpixelOne;
      if (n % 5 == 0) w.y = (w.y / kSubpixelOne) * kSubpixelOne + kSubpixelHalf;  // on a row's centres
      w.fx = double(w.x) / kSubpixelOne;
      w.fy = double(w.y) / kSubpixelOne;
    }
    if (n % 7 == 0) v[2].x = v[1].x + (v[1].x - v[0].x) / 97;  // slivers
    TriangleSetup t;
    if (!setupTriangle(v[0], v[1], v[2], FrontFacing, rs, codec, t)) continue;
    const int y0 = int(next() % 80), y1 = std::min(79, y0 + int(next() % 24));
    const ColumnRange c = columnsInRows(t, region, y0, y1);
    int lo = region.width, hi = -1;
    for (int y = y0; y <= y1; ++y)
      for (int x = 0; x < region.width; ++x) {
        bool inside = true;
        for (int i = 0; i < 3; ++i) inside = inside && t.edgeAt(i, x, y) + t.bias[i] >= 0;
        if (!inside) continue;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
        ++coveredTotal;
      }
    INFO("triangle " << n << ": (" << v[0].x << "," << v[0].y << ") (" << v[1].x << "," << v[1].y << ") (" << v[2].x
                     << "," << v[2].y << "), rows " << y0 << ".." << y1);
    if (hi >= 0) {
      REQUIRE(c.first <= lo);
      REQUIRE(c.last >= hi);
    }
    if (c.first <= c.last) {  // inside the bounding box and the region
      CHECK(c.first >= std::max(t.minX, region.x));
      CHECK(c.last <= std::min(t.maxX, region.x + region.width - 1));
    }
    narrowed += c.last - c.first < std::min(t.maxX, 95) - std::max(t.minX, 0) - 8;
    ++checked;
  }
  CHECK(checked > 2500);
  CHECK(coveredTotal > 100000);
  CHECK(narrowed > 300);  // the band's rows cut many triangles to far fewer columns than their box
}

TEST_CASE("a diagonal sliver's columns in the bottom rows are the few its edges cross there", "[raster][coverage][columns]") {
  // Edges from (0, 0) to (800, 640) and (810, 640): x = 1.25 y and x = 1.265625 y. At the sample
  // line of row 15 (y = 15.5) they are at x = 19.375 and 19.617, so the last column whose centre
  // (px + 1/2) can be inside is 19; the range adds a pixel for rounding: 20. The bottom sample
  // line (y = 0.5) meets them at x = 0.625: first column 1, with the pixel 0.
  RenderState rs;
  const DepthCodec codec;
  TriangleSetup t;
  REQUIRE(setupTriangle(vertexAt(0, 0), vertexAt(800, 640), vertexAt(810, 640), FrontFacing, rs, codec, t));
  const ColumnRange bottom = columnsInRows(t, Rect{0, 0, 1024, 1024}, 0, 15);
  CHECK(bottom.first == 0);
  CHECK(bottom.last == 20);
  // Rows 320..335 (sample lines y = 320.5 and 335.5): x from 400.625 to 424.617, centres in
  // columns 401..424, with the pixel each side 400..425.
  const ColumnRange middle = columnsInRows(t, Rect{0, 0, 1024, 1024}, 320, 335);
  CHECK(middle.first == 400);
  CHECK(middle.last == 425);
  // Rows the triangle does not reach: nothing.
  const ColumnRange above = columnsInRows(t, Rect{0, 0, 1024, 1024}, 700, 710);
  CHECK(above.first > above.last);
}

TEST_CASE("row spans cut into bands of rows cover what the edge functions say, also in a row through the middle vertex",
          "[raster][coverage][spans]") {
  // A triangle without a horizontal edge is walked with two edge limits a row: of the two edges
  // meeting at the middle vertex, the lower below it and the upper from its row up. Bands of
  // every height start the walk below, at and above that row; the vertices lie on pixel centres
  // half the time, so a row through the middle vertex — and a middle vertex on a pixel centre,
  // where the top-left rule decides — come up often. Oracle: the three biased edge values at each
  // pixel centre. (Starting the upper edge a row early or late, or from the walk's first row,
  // fails here.)
  const Rect region{0, 0, 40, 40};
  XorShift next{0xD1B54A32D192ED03ull};
  // Two pixels either side of the region: on a pixel centre, or anywhere on the subpixel grid.
  auto coordinate = [&](bool centre) {
    const int64_t at = centre ? int64_t(next() % 44) * kSubpixelOne + kSubpixelHalf : int64_t(next() % (44 * kSubpixelOne));
    return at - 2 * kSubpixelOne;
  };
  RenderState rs;
  const DepthCodec codec;
  int throughMiddle = 0, checked = 0;
  for (int n = 0; n < 1500; ++n) {
    WindowVertex v[3];
    for (WindowVertex& w : v) {
      const bool centre = next() % 2 == 0;
      w.x = coordinate(centre);
      w.y = coordinate(centre);
      w.fx = double(w.x) / kSubpixelOne;
      w.fy = double(w.y) / kSubpixelOne;
    }
    TriangleSetup t;
    if (!setupTriangle(v[0], v[1], v[2], FrontFacing, rs, codec, t)) continue;
    const int64_t ys[3] = {t.v[0].y, t.v[1].y, t.v[2].y};
    if (ys[0] == ys[1] || ys[1] == ys[2] || ys[0] == ys[2]) continue;  // a horizontal edge: the general walk
    const int64_t middle = std::max(std::min(ys[0], ys[1]), std::min(std::max(ys[0], ys[1]), ys[2]));
    throughMiddle += (middle - kSubpixelHalf) % kSubpixelOne == 0;
    const int height = 1 + int(next() % 7);
    std::vector<uint8_t> covered(size_t(region.width * region.height), 0);
    for (int y0 = 0; y0 < region.height; y0 += height) {
      const Rect band{0, y0, region.width, std::min(height, region.height - y0)};
      rasterizeRowSpans(t, band, [&](int y, int xl, int xr) {
        REQUIRE(y >= band.y);
        REQUIRE(y < band.y + band.height);
        for (int x = xl; x <= xr; ++x) ++covered[size_t(y * region.width + x)];
      });
    }
    int wrong = 0;
    for (int y = 0; y < region.height; ++y)
      for (int x = 0; x < region.width; ++x) {
        bool inside = true;
        for (int i = 0; i < 3; ++i) inside = inside && t.edgeAt(i, x, y) + t.bias[i] >= 0;
        wrong += covered[size_t(y * region.width + x)] != (inside ? 1 : 0);
      }
    INFO("triangle " << n << ": (" << v[0].x << "," << v[0].y << ") (" << v[1].x << "," << v[1].y << ") (" << v[2].x
                     << "," << v[2].y << "), bands of " << height);
    REQUIRE(wrong == 0);
    ++checked;
  }
  CHECK(checked > 1000);
  CHECK(throughMiddle > 100);
}
