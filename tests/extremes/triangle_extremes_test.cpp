// Degenerate, sliver and huge triangles, and vertices with w = 0 or w near 0, at the raster level
// (docs/numerics.md, "Triangles"): w = 0 vertices are legal input, and triangles that share an
// edge cover every pixel on it exactly once, which stencil counting depends on.
//
// Every test counts coverage with stencil INCR on a 64 x 64 framebuffer (raster_harness.h), so a
// pixel covered twice or missed shows as a 2 or a 0.
#include <catch2/catch.hpp>

#include <vector>

#include "gl/pipeline.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

constexpr int kSize = 64;

ClipVertex clip(double x, double y, double z, double w) {
  ClipVertex v;
  v.position = {x, y, z, w};
  return v;
}

// Pixels whose stencil is not `expected(x, y)`.
template <class Expected>
int wrongPixels(const Framebuffer& fb, Expected&& expected) {
  int wrong = 0;
  for (int y = 0; y < fb.height(); ++y)
    for (int x = 0; x < fb.width(); ++x) wrong += fb.stencilAt(x, y) != expected(x, y);
  return wrong;
}

}  // namespace

TEST_CASE("Degenerate triangles (a point, collinear along pixel centres, repeated vertices) cover no pixel",
          "[extremes]") {
  Framebuffer fb(kSize, kSize);
  const auto pipeline = makePipeline(PipelineKind::Fast, fb);
  const RenderState state = coverageCountingState(fb);
  const Viewport& vp = state.viewport;
  const std::vector<ClipVertex> triangles =
      windowTriangles(vp, {{10.5, 10.5, 0.5}, {10.5, 10.5, 0.5}, {10.5, 10.5, 0.5},     // a point on a centre
                           {2.5, 20.5, 0.5}, {30.5, 20.5, 0.5}, {60.5, 20.5, 0.5},      // along a row of centres
                           {3.5, 3.5, 0.5}, {40.5, 40.5, 0.5}, {20.5, 20.5, 0.5},       // along the diagonal
                           {5.0, 50.0, 0.5}, {50.0, 5.0, 0.5}, {5.0, 50.0, 0.5}});      // two equal corners
  draw(*pipeline, state, triangles);
  CHECK(wrongPixels(pipeline->framebuffer(), [](int, int) { return 0; }) == 0);
  CHECK(pipeline->stats().fragments == 0);
}

TEST_CASE("A fan of sliver triangles (thousandths of a pixel wide) covers its square exactly once", "[extremes][slow]") {
#if defined(__SANITIZE_ADDRESS__)
  constexpr int kPerSide = 4000;
#else
  constexpr int kPerSide = 48000;  // 1/1000 pixel along the rim
#endif
  Framebuffer fb(kSize, kSize);
  const auto pipeline = makePipeline(PipelineKind::Fast, fb);
  const RenderState state = coverageCountingState(fb);
  // The square [8, 56]^2 walked counter-clockwise; every rim step and the centre form a triangle.
  std::vector<glm::dvec2> rim;
  const glm::dvec2 corners[4] = {{8, 8}, {56, 8}, {56, 56}, {8, 56}};
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < kPerSide; ++k)
      rim.push_back(corners[side] + (corners[(side + 1) % 4] - corners[side]) * (double(k) / kPerSide));
  const glm::dvec2 centre{31.3, 30.7};
  std::vector<ClipVertex> fan;
  for (size_t k = 0; k < rim.size(); ++k) {
    const glm::dvec2& a = rim[k];
    const glm::dvec2& b = rim[(k + 1) % rim.size()];
    for (const glm::dvec2& p : {centre, a, b}) fan.push_back(windowVertex(state.viewport, p.x, p.y));
  }
  draw(*pipeline, state, fan);
  INFO(stencilPicture(pipeline->framebuffer()));
  CHECK(wrongPixels(fb, [](int x, int y) { return x >= 8 && x < 56 && y >= 8 && y < 56 ? 1 : 0; }) == 0);
}

TEST_CASE("Huge triangles (corners at 1e25 in clip space) are clipped to the guard band and two that share a "
          "diagonal through pixel centres cover every pixel exactly once", "[extremes]") {
  for (double h : {1e6, 1e15, 1e25, 1e300}) {
    Framebuffer fb(kSize, kSize);
    const auto pipeline = makePipeline(PipelineKind::Fast, fb);
    const RenderState state = coverageCountingState(fb);
    // The diagonal x = y runs through the centres (i + 0.5, i + 0.5): the fill rule must give each
    // of them to exactly one of the two triangles, after both were cut at the same points.
    const std::vector<ClipVertex> square = {clip(-h, -h, 0, 1), clip(h, -h, 0, 1), clip(h, h, 0, 1),
                                            clip(-h, -h, 0, 1), clip(h, h, 0, 1),  clip(-h, h, 0, 1)};
    draw(*pipeline, state, square);
    INFO("corner " << h << "\n" << stencilPicture(pipeline->framebuffer()));
    CHECK(wrongPixels(fb, [](int, int) { return 1; }) == 0);
  }
}

TEST_CASE("A vertex with w = 0 or |w| <= 1e-6 (a point at or near infinity) opens the triangle into a strip, "
          "it covers exactly the strip's pixels", "[extremes]") {
  // A = (-0.5, -0.5), B = (0.5, -0.5) in NDC and C = (0, 1, 0, w): with w = 0 the triangle is
  // the half-strip above AB towards +y; for w = ±1e-6 its sides lean by under 1e-4 pixel across the
  // image, for smaller |w| by less. On 64 x 64: columns 16 .. 47, rows 16 .. 63.
  for (double w : {0.0, 1e-300, 1e-30, 1e-12, 1e-6, -1e-300, -1e-12, -1e-6}) {
    Framebuffer fb(kSize, kSize);
    const auto pipeline = makePipeline(PipelineKind::Fast, fb);
    const RenderState state = coverageCountingState(fb);
    const std::vector<ClipVertex> triangle = {clip(-0.5, -0.5, 0, 1), clip(0.5, -0.5, 0, 1), clip(0.0, 1.0, 0.0, w)};
    draw(*pipeline, state, triangle);
    INFO("w = " << w << "\n" << stencilPicture(pipeline->framebuffer()));
    CHECK(wrongPixels(fb, [](int x, int y) { return x >= 16 && x < 48 && y >= 16 ? 1 : 0; }) == 0);
  }
}
