// The bands a flush's rows are cut into (exec/row_work.h). The work estimate behind them is a
// heuristic, free to change: every split gives the same bytes. So what is tested here holds for any
// weights: whatever the rows weigh, a split covers them once, in order, in non-empty bands of at
// least the rows asked for; counts made in groups or after a reset are the counts made at once;
// and frames drawn through the fast executor with the splits of 1, 2, 3 and 8 threads are the same
// in every byte.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include <catch2/catch.hpp>

#include "exec/renderer.h"
#include "exec/row_work.h"
#include "gl/clear.h"
#include "gl/projection.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {
const Rect kRegion{0, 0, 100, 64};

SetupBounds box(int minX, int minY, int maxX, int maxY) { return {minX, minY, maxX, maxY}; }

// What the estimate reads of a tall triangle's setup: its vertices' rows (all three here on the
// row peakY) and its area.
TriangleSetup shape(int peakY, int64_t pixels) {
  TriangleSetup t;
  for (WindowVertex& v : t.v) v.y = int64_t(peakY) * kSubpixelOne + kSubpixelHalf;
  t.area2 = pixels << (2 * kSubpixelBits + 1);
  return t;
}
const TriangleSetup kShort = shape(0, 1);  // a short triangle's setup is not read

// A count of random triangles (short and tall, inside the region and reaching out of it, weighed
// by shape or by box), clears, and on some seeds a stencil test that weighs the rows.
RowWork randomCount(uint64_t seed, int rows, std::vector<uint8_t>& stencil) {
  TestRandom rng(seed);
  const Rect region{0, 0, 100, rows};
  RowWork work;
  work.reset(rows);
  const bool byShape = rng.below(2) == 0;
  const int triangles = rng.below(40);
  for (int i = 0; i < triangles; ++i) {
    const int x0 = rng.below(140) - 20, y0 = rng.below(rows + 20) - 10;
    const int x1 = x0 + rng.below(120), y1 = y0 + rng.below(rows);
    work.addTriangle(box(x0, y0, x1, y1), shape(y0 + rng.below(y1 - y0 + 1), 1 + rng.below(4000)), region, byShape);
  }
  for (int i = rng.below(3); i > 0; --i) {
    const int y = rng.below(rows);
    work.addClear(Rect{rng.below(50), y, 1 + rng.below(100), 1 + rng.below(rows - y)});
  }
  if (rng.below(3) == 0) {
    stencil.resize(size_t(100) * size_t(rows));
    for (uint8_t& s : stencil) s = uint8_t(rng.below(3));
    StencilFaceState test;
    test.func = CompareFunc::Equal;
    work.weighByStencil(stencil.data(), 100, 0, rows - 1, test);
  }
  return work;
}
}  // namespace

TEST_CASE("a split covers its rows once, in order, in at most the bands asked for, none empty or short",
          "[raster][bands]") {
  int splits = 0, several = 0;
  for (uint64_t seed = 1; seed <= 60; ++seed) {
    const int rows = 1 + int(seed * 37 % 300);
    std::vector<uint8_t> stencil;
    RowWork work = randomCount(seed, rows, stencil);
    TestRandom rng(seed + 1000);
    for (int k = 0; k < 12; ++k) {
      const int minY = rng.below(rows), maxY = minY + rng.below(rows - minY);
      const int maxBands = 1 + rng.below(8), minRows = std::vector<int>{1, 2, 4, 16}[size_t(rng.below(4))];
      for (const RowWork::Shares shares : {RowWork::Shares::Shrinking, RowWork::Shares::Equal}) {
        INFO("seed " << seed << ", rows " << minY << " ... " << maxY << ", " << maxBands << " bands of at least "
                     << minRows << (shares == RowWork::Shares::Equal ? ", equal shares" : ", shrinking shares"));
        std::vector<int> first{-7, -7, -7};  // what was in it before is replaced
        const int n = work.split(minY, maxY, maxBands, minRows, first, shares);
        REQUIRE(n >= 1);
        REQUIRE(n <= maxBands);
        REQUIRE(first.size() == size_t(n) + 1);
        CHECK(first.front() == minY);
        CHECK(first.back() == maxY + 1);
        for (int b = 0; b < n; ++b) {
          CHECK(first[size_t(b) + 1] > first[size_t(b)]);  // not empty, and in order
          if (n > 1) CHECK(first[size_t(b) + 1] - first[size_t(b)] >= minRows);
        }
        ++splits;
        several += n > 1;
      }
    }
  }
  CHECK(splits == 60 * 12 * 2);
  CHECK(several > splits / 4);  // most cases cut: the checks above were not all of single bands
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

namespace {

// The buffers' bytes of one frame drawn through the fast executor at `threads` threads.
struct Frame {
  std::vector<uint8_t> color, depth, stencil;
};

template <class T>
std::vector<uint8_t> bytes(const PixelVector<T>& v) {
  std::vector<uint8_t> out(v.size() * sizeof(T));
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size());
  return out;
}

// Three streams of draws, each a kind of flush the bands are cut for:
//   0: random triangles, some crossing the near plane, random depth and stencil tests and
//      order-dependent blending (a pixel's fragments must meet in submission order);
//   1: shadow-volume-like slivers across the screen, counted with wrapping ops on both faces (a
//      flush of tall triangles, counted by runs of triangles), a clear of part of the colour in
//      between, then a lit pass where the stencil equals 0 (rows weighed by the stencil);
//   2: a dense grid of small triangles counted with saturating INCR (counted by bands).
Frame drawStream(int stream, int width, int height, int threads, uint64_t seed) {
  Framebuffer fb(width, height);
  TestRandom rng(seed);
  RenderState s = fullViewportState(fb);
  clearColor(fb, s, {0.1f, 0.2f, 0.3f, 0.4f});
  clearDepth(fb, s, 1.0);
  clearStencil(fb, s, 0);
  const ColorVaryingShader shader;
  {
    Renderer r(fb, threads);
    const glm::dmat4 p = perspective(70.0, double(width) / height, 0.5, 50.0);
    auto randomVertices = [&](int triangles, double spread) {
      std::vector<ClipVertex> v(size_t(3 * triangles));
      for (ClipVertex& cv : v) {
        cv.position = p * glm::dvec4(rng.uniform(-spread, spread), rng.uniform(-spread, spread), rng.uniform(-12, 1), 1.0);
        for (int k = 0; k < 4; ++k) cv.varyings[k] = rng.uniform(-0.2, 1.2);
      }
      return v;
    };
    if (stream == 0) {
      for (int d = 0; d < 30; ++d) {
        s.depthTest = rng.below(4) != 0;
        s.depthFunc = CompareFunc(rng.below(8));
        s.stencilTest = rng.below(2) != 0;
        for (StencilFaceState& f : s.stencil) {
          f.func = CompareFunc(rng.below(8));
          f.ref = rng.below(4);
          f.dppass = StencilOp(rng.below(8));
        }
        s.cull = CullMode(rng.below(3));
        s.blend = {true, BlendFactor(rng.below(10)), BlendFactor(rng.below(10))};
        draw(r, s, randomVertices(12, 6.0), &shader);
      }
    } else if (stream == 1) {
      s.depthTest = true;
      s.depthFunc = CompareFunc::Less;
      draw(r, s, randomVertices(20, 4.0), &shader);  // the scene's depth
      RenderState volume = s;
      volume.depthWrite = false;
      volume.colorMask = {false, false, false, false};
      volume.stencilTest = true;
      volume.stencil[0].dppass = StencilOp::IncrWrap;
      volume.stencil[1].dppass = StencilOp::DecrWrap;
      std::vector<ClipVertex> slivers;
      for (int i = 0; i < 150; ++i) {
        const double x = rng.uniform(-2, width + 2), top = rng.uniform(height * 0.5, height + 4.0);
        const std::vector<ClipVertex> t = windowTriangles(
            s.viewport, {{x, -3.0, rng.uniform(0, 1)}, {x + rng.uniform(1, 6), top, rng.uniform(0, 1)},
                         {x + rng.uniform(-5, 5), rng.uniform(-3, top), rng.uniform(0, 1)}});
        slivers.insert(slivers.end(), t.begin(), t.end());
      }
      draw(r, volume, slivers);
      RenderState part = s;
      part.scissorTest = true;
      part.scissor = Rect{width / 5, height / 3, width / 2, height / 3};
      r.clear({.state = part, .color = glm::vec4(0.9f, 0.1f, 0.5f, 1.0f)});
      RenderState lit = s;
      lit.depthFunc = CompareFunc::LEqual;
      lit.stencilTest = true;
      lit.stencil[0].func = lit.stencil[1].func = CompareFunc::Equal;
      lit.blend = {true, BlendFactor::One, BlendFactor::One};
      draw(r, lit, randomVertices(20, 4.0), &shader);
    } else {
      RenderState counting = coverageCountingState(fb);
      std::vector<ClipVertex> grid;
      for (int y = 0; y + 3 < height; y += 3)
        for (int x = 0; x + 3 < width; x += 3) {
          const std::vector<ClipVertex> t =
              windowTriangles(s.viewport, {{x + 0.25, y + 0.5, 0.5}, {x + 4.5, y + 0.75, 0.5}, {x + 1.5, y + 4.0, 0.5}});
          grid.insert(grid.end(), t.begin(), t.end());
        }
      for (int k = 0; k < 3; ++k) draw(r, counting, grid);
    }
  }
  return {bytes(fb.color()), bytes(fb.depthCodes()), bytes(fb.stencil())};
}

}  // namespace

TEST_CASE("any split of the rows gives the same bytes: 1, 2, 3 and 8 threads draw every stream alike",
          "[raster][bands][determinism]") {
  struct Size {
    int width, height;
  };
  for (const Size size : {Size{97, 61}, Size{64, 200}, Size{160, 17}}) {
    for (int stream : {0, 1, 2}) {
      const uint64_t seed = uint64_t(size.width * 1000 + size.height * 10 + stream);
      const Frame one = drawStream(stream, size.width, size.height, 1, seed);
      // Not a vacuous comparison: the stream writes its buffers, and another seed other bytes.
      if (stream != 2) CHECK(one.color != drawStream(stream, size.width, size.height, 1, seed + 1).color);
      CHECK(std::any_of(one.stencil.begin(), one.stencil.end(), [](uint8_t v) { return v != 0; }));
      for (int threads : {2, 3, 8}) {
        INFO(size.width << "x" << size.height << ", stream " << stream << ", " << threads << " threads");
        const Frame many = drawStream(stream, size.width, size.height, threads, seed);
        CHECK(many.color == one.color);
        CHECK(many.depth == one.depth);
        CHECK(many.stencil == one.stencil);
      }
    }
  }
}
