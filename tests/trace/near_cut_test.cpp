// The near-plane class of the replay report (trace/edge_mask.h, NearCutBound): a hand-built trace
// with one triangle cut by the near plane, the bound of a float clipper worked out by hand, and
// the classification of depth differences inside and outside it.
#include <catch2/catch.hpp>

#include "trace/edge_mask.h"
#include "trace/trace_compare.h"

namespace shadowref::trace {

namespace {

constexpr int kSize = 64;

// Corners a, b in front of the near plane (z + w = 1), c behind it (z + w = -2); w = 1 throughout,
// so window coordinates are affine: a (16, 16, 0.5), b (48, 16, 0.5), c (32, 48, -1). The plane:
// dz/dx = 0, dz/dy = -1.5 / 32. The near plane cuts a-c and b-c at t = 1/3, in
// (-1/3, -1/6, -1, 1) and (1/3, -1/6, -1, 1): window y = 32 (1 - 1/6) = 26.67.
const glm::dvec4 kA(-0.5, -0.5, 0.0, 1.0), kB(0.5, -0.5, 0.0, 1.0), kC(0.0, 0.5, -3.0, 1.0);

RenderState fullState() {
  RenderState s;
  s.viewport = {0, 0, kSize, kSize, 0.0, 1.0};
  s.depthTest = true;
  return s;
}

size_t pixel(int x, int y) { return size_t(y) * kSize + size_t(x); }

// The bound by hand: the edges' largest coordinate is 3 (c.z), so e = 3 * 2^-22; at either new
// vertex (w = 1) depth errs by e (1 + |z/w|) = 2e in NDC, 0.5 * 2e = e in window depth; y by
// e (1 + 1/6) in NDC, 32 e (7/6) pixels, times |dz/dy| = 1.5/32: 1.75 e. Together 2.75 e,
// in codes 2.75 * 3 * 2^-22 * (2^24 - 1) = 33 - 8.25 * 2^-22.
const double kBoundCodes = 33.0 - 8.25 * 0x1p-22;

}  // namespace

TEST_CASE("near-plane cut: the bound of a float clipper, by hand", "[trace][nearcut]") {
  NearCutBound bound(kSize, kSize);
  bound.addTriangle(kA, kB, kC, fullState());
  CHECK(bound.at(pixel(32, 20)) == Approx(kBoundCodes).epsilon(1e-9));
  CHECK(bound.at(pixel(20, 17)) == Approx(kBoundCodes).epsilon(1e-9));
  CHECK(bound.at(pixel(32, 27)) == 0.0);  // beyond the cut (window y 26.67): nothing drawn there
  CHECK(bound.at(pixel(5, 5)) == 0.0);

  // Polygon offset adds the whole slope term: |factor| * max(|dz/dx|, |dz/dy|) codes.
  RenderState offset = fullState();
  offset.polygonOffset = PolygonOffset{true, -2.0, 4.0};
  NearCutBound withOffset(kSize, kSize);
  withOffset.addTriangle(kA, kB, kC, offset);
  CHECK(withOffset.at(pixel(32, 20)) == Approx(kBoundCodes + 2.0 * (1.5 / 32) * 16777215.0).epsilon(1e-9));

  // No cut, no bound: a triangle in front of the near plane, and the same triangle under depth clamp.
  NearCutBound uncut(kSize, kSize), clamped(kSize, kSize);
  uncut.addTriangle(kA, kB, glm::dvec4(0.0, 0.5, 0.5, 1.0), fullState());
  RenderState clamp = fullState();
  clamp.depthClamp = true;
  clamped.addTriangle(kA, kB, kC, clamp);
  CHECK(uncut.at(pixel(32, 20)) == 0.0);
  CHECK(clamped.at(pixel(32, 20)) == 0.0);
}

TEST_CASE("near-plane cut: depth differences within the bound are their own class", "[trace][nearcut]") {
  Trace trace;
  trace.targets.push_back({kSize, kSize, DepthFormat::Unorm24});
  DrawCommand draw;
  draw.state = fullState();
  draw.vertices.resize(3);
  draw.vertices[0].position = kA;
  draw.vertices[1].position = kB;
  draw.vertices[2].position = kC;
  trace.commands.push_back({0, 0, draw});
  Buffers expected;
  expected.width = expected.height = kSize;
  expected.depthFormat = DepthFormat::Unorm24;
  expected.depth.assign(size_t(kSize) * kSize, 8000000);
  Buffers actual = expected;
  actual.depth[pixel(32, 20)] += 2 + 30;  // tolerance 2 + 30 <= 2 + 33: the near-plane class
  actual.depth[pixel(36, 20)] -= 2 + 34;  // beyond tolerance + bound: elsewhere
  actual.depth[pixel(8, 50)] += 3;        // no cut triangle there: elsewhere

  const Comparison gl = compareBuffers(trace, {&expected}, {actual}, {Tolerances{false, 1.0, 2}});
  const BufferComparison& depth = gl.targets.at(0).buffers.at(1);
  REQUIRE(depth.buffer == "depth");
  CHECK(depth.differing == 3);
  CHECK(depth.differingOnEdge == 0);
  CHECK(depth.differingNearCut == 1);
  CHECK(depth.differingOffEdge == 2);
  CHECK(depth.differs[pixel(32, 20)] == 3);
  CHECK(depth.differs[pixel(36, 20)] == 2);
  CHECK_THAT(reportText(gl), Catch::Contains("1 on a near-plane cut"));

  // Between shadowref's pipelines nothing is explained: every differing byte counts.
  const Comparison exact = compareBuffers(trace, {&expected}, {actual}, {Tolerances{}});
  CHECK(exact.targets.at(0).buffers.at(1).differingNearCut == 0);
  CHECK(exact.targets.at(0).buffers.at(1).differingOffEdge == 3);
}

}  // namespace shadowref::trace
