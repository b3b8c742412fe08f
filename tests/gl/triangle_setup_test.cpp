// Triangle setup: facing and culling, and the GL 1.1 polygon offset computed from the snapped
// window-space triangle.
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/projection.h"
#include "exec/rasterizer.h"
#include "exec/renderer.h"
#include "gl/triangle_setup.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

const char* cullName(CullMode c) {
  switch (c) {
    case CullMode::None: return "NONE";
    case CullMode::Front: return "FRONT";
    case CullMode::Back: return "BACK";
    case CullMode::FrontAndBack: return "FRONT_AND_BACK";
  }
  return "?";
}

// Whether a triangle of the given winding reaches the stencil under (cull, frontFace).
bool drawn(CullMode cull, FrontFace frontFace, bool counterClockwise, bool clippedByNearPlane) {
  Framebuffer fb(8, 8);
  RenderState s = coverageCountingState(fb);
  s.cull = cull;
  s.frontFace = frontFace;
  std::vector<ClipVertex> v;
  if (!clippedByNearPlane) {
    v = windowTriangles(s.viewport, {{1, 1, 0.5}, {7, 1, 0.5}, {1, 7, 0.5}});  // counter-clockwise
  } else {
    // The same window triangle, but its third vertex lies behind the eye (w < 0), so the clipper
    // replaces it; the facing must come from the clipped polygon, which keeps the winding.
    const glm::dmat4 p = frustum(-1, 1, -1, 1, 1, 100);
    v.resize(3);
    v[0].position = p * glm::dvec4(-1.5, -1.5, -2, 1);
    v[1].position = p * glm::dvec4(1.5, -1.5, -2, 1);
    v[2].position = p * glm::dvec4(-0.5, 4.0, 1, 1);
  }
  if (!counterClockwise) std::swap(v[1], v[2]);
  Renderer r(fb);
  draw(r, s, v);
  int covered = 0;
  for (uint8_t c : fb.stencil()) covered += c;
  return covered > 0;
}

}  // namespace

TEST_CASE("culling x front face: a triangle is drawn unless its facing is culled", "[raster][cull]") {
  struct Case {
    CullMode cull;
    FrontFace frontFace;
    bool ccw;
    bool drawn;
  };
  const Case cases[] = {
      {CullMode::None, FrontFace::CCW, true, true},           {CullMode::None, FrontFace::CCW, false, true},
      {CullMode::None, FrontFace::CW, true, true},            {CullMode::None, FrontFace::CW, false, true},
      {CullMode::Front, FrontFace::CCW, true, false},         {CullMode::Front, FrontFace::CCW, false, true},
      {CullMode::Front, FrontFace::CW, true, true},           {CullMode::Front, FrontFace::CW, false, false},
      {CullMode::Back, FrontFace::CCW, true, true},           {CullMode::Back, FrontFace::CCW, false, false},
      {CullMode::Back, FrontFace::CW, true, false},           {CullMode::Back, FrontFace::CW, false, true},
      {CullMode::FrontAndBack, FrontFace::CCW, true, false},  {CullMode::FrontAndBack, FrontFace::CCW, false, false},
      {CullMode::FrontAndBack, FrontFace::CW, true, false},   {CullMode::FrontAndBack, FrontFace::CW, false, false},
  };
  for (const Case& c : cases) {
    INFO("cull " << cullName(c.cull) << ", front face " << (c.frontFace == FrontFace::CCW ? "CCW" : "CW")
                 << ", triangle " << (c.ccw ? "CCW" : "CW"));
    CHECK(drawn(c.cull, c.frontFace, c.ccw, false) == c.drawn);
    CHECK(drawn(c.cull, c.frontFace, c.ccw, true) == c.drawn);
  }
}

TEST_CASE("facing follows the signed window area with row 0 at the bottom", "[raster][cull]") {
  Framebuffer fb(8, 8);
  const Viewport vp = fullViewportState(fb).viewport;
  const ClipVertex a = windowVertex(vp, 1, 1), b = windowVertex(vp, 7, 1), c = windowVertex(vp, 1, 7);
  const WindowVertex wa = toWindow(a, vp), wb = toWindow(b, vp), wc = toWindow(c, vp);
  CHECK(signedArea2(wa, wb, wc) == 6 * 6 * 256 * 256);  // counter-clockwise, y up
  CHECK(signedArea2(wa, wc, wb) == -6 * 6 * 256 * 256);
  CHECK(facingOf(signedArea2(wa, wb, wc), FrontFace::CCW) == FrontFacing);
  CHECK(facingOf(signedArea2(wa, wb, wc), FrontFace::CW) == BackFacing);
  CHECK(facingOf(signedArea2(wa, wc, wb), FrontFace::CW) == FrontFacing);
}

// ---------------------------------------------------------------------------------------------
// Polygon offset, [GL 2.1, §3.5.5]: o = factor * m + units * r, m = max(|dz/dx|, |dz/dy|).

namespace {

// Window triangle (0,0) (16,0) (0,16) with depth 0.25 + a x + b y.
TriangleSetup slopedTriangle(const Viewport& vp, double a, double b, const RenderState& s, const DepthCodec& codec) {
  const ClipVertex v0 = windowVertex(vp, 0, 0, 0.25);
  const ClipVertex v1 = windowVertex(vp, 16, 0, 0.25 + 16 * a);
  const ClipVertex v2 = windowVertex(vp, 0, 16, 0.25 + 16 * b);
  TriangleSetup t;
  REQUIRE(setupTriangle(toWindow(v0, vp), toWindow(v1, vp), toWindow(v2, vp), FrontFacing, s, codec, t));
  return t;
}

}  // namespace

TEST_CASE("polygon offset = factor * max depth slope + units * r (GL 1.1 formula)", "[raster][depth][offset]") {
  Framebuffer fb(16, 16);
  RenderState s = fullViewportState(fb);
  const PolygonOffset po{true, 2.0, 3.0};
  const DepthCodec u{DepthFormat::Unorm24}, f{DepthFormat::Float32};
  // dz/dx = 1/64, dz/dy = -1/128: m = 1/64; vertex depths 0.25, 0.5, 0.125, so z_max = 0.5.
  {
    const TriangleSetup t = slopedTriangle(s.viewport, 1.0 / 64, -1.0 / 128, s, u);
    CHECK(polygonOffset(t, po, u) == 2.0 / 64 + 3.0 / 16777215.0);
    CHECK(polygonOffset(t, po, f) == 2.0 / 64 + 3.0 * std::ldexp(1.0, -24));  // 0.5 has exponent -1
  }
  // dz/dx = 1/128, dz/dy = -1/64: the y slope is the larger in magnitude; depths 0.25, 0.375,
  // 0.0, so z_max = 0.375 -> r = 2^-25.
  {
    const TriangleSetup t = slopedTriangle(s.viewport, 1.0 / 128, -1.0 / 64, s, u);
    CHECK(polygonOffset(t, po, u) == 2.0 / 64 + 3.0 / 16777215.0);
    CHECK(polygonOffset(t, po, f) == 2.0 / 64 + 3.0 * std::ldexp(1.0, -25));
  }
  // A triangle of constant depth has m = 0: only the units term is left.
  {
    const TriangleSetup t = slopedTriangle(s.viewport, 0.0, 0.0, s, u);
    CHECK(polygonOffset(t, {true, 100.0, -1.0}, u) == -1.0 / 16777215.0);
  }
  // The setup stores it only when polygon offset is enabled.
  s.polygonOffset = po;
  const TriangleSetup on = slopedTriangle(s.viewport, 1.0 / 64, -1.0 / 128, s, u);
  CHECK(on.depthOffset == 2.0 / 64 + 3.0 / 16777215.0);
  s.polygonOffset.enabled = false;
  const TriangleSetup off = slopedTriangle(s.viewport, 1.0 / 64, -1.0 / 128, s, u);
  CHECK(off.depthOffset == 0.0);
}

TEST_CASE("polygon offset shifts every fragment's depth by o before it is stored", "[raster][depth][offset]") {
  for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
    INFO((format == DepthFormat::Float32 ? "float32" : "unorm24"));
    Framebuffer fb(16, 16, format);
    RenderState s = fullViewportState(fb);
    s.depthTest = true;
    s.depthFunc = CompareFunc::Always;
    s.polygonOffset = {true, 2.0, 3.0};
    const double a = 1.0 / 64, b = -1.0 / 128;
    const double r = format == DepthFormat::Unorm24 ? 1.0 / 16777215.0 : std::ldexp(1.0, -24);
    const double o = 2.0 * (1.0 / 64) + 3.0 * r;
    Renderer rr(fb);
    draw(rr, s, windowTriangles(s.viewport, {{0, 0, 0.25}, {16, 0, 0.25 + 16 * a}, {0, 16, 0.25 + 16 * b}}));
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x + y < 15; ++x) {  // centres strictly inside x + y < 16
        INFO("pixel " << x << "," << y);
        const double z = 0.25 + a * (x + 0.5) + b * (y + 0.5) + o;
        CHECK(fb.depthCodes()[fb.index(x, y)] == fb.depthCodec().encode(z));
      }
  }
}

TEST_CASE("polygon offset below 0 or above 1 is clamped to the depth range", "[raster][depth][offset]") {
  Framebuffer fb(4, 4);
  RenderState s = fullViewportState(fb);
  s.depthTest = true;
  s.depthFunc = CompareFunc::Always;
  s.polygonOffset = {true, 0.0, -1e9};  // o = -1e9 * 2^-25
  Renderer r(fb);
  draw(r, s, windowRect(s.viewport, 0, 0, 4, 4, 0.25));
  CHECK(fb.depthAt(1, 1) == 0.0);
  s.polygonOffset = {true, 0.0, 1e9};
  draw(r, s, windowRect(s.viewport, 0, 0, 4, 4, 0.25));
  CHECK(fb.depthAt(1, 1) == 1.0);
}

// TriangleSetup::depthsInUnit lets the span loops leave out the depth codec's clamp, so it may be
// set only where every covered pixel's depth (planeDepthAt + offset, as computed) is in (0, 1].
TEST_CASE("depthsInUnit is set only where every covered depth is above 0 and at most 1", "[raster][depth][spans]") {
  Framebuffer fb(64, 64);
  RenderState s = fullViewportState(fb);
  const DepthCodec codec{DepthFormat::Float32};
  auto setup = [&](std::initializer_list<glm::dvec3> points, TriangleSetup& t) {
    const std::vector<ClipVertex> v = windowTriangles(s.viewport, points);
    return setupTriangle(toWindow(v[0], s.viewport), toWindow(v[1], s.viewport), toWindow(v[2], s.viewport),
                         FrontFacing, s, codec, t);
  };
  TriangleSetup t;
  // Hand-made cases: a large triangle well inside the range; one that reaches the far plane
  // exactly (1 would be kept, but no margin is left: not shown); one that reaches 0; one too small
  // to be asked (a bounding box under 256 pixels).
  REQUIRE(setup({{0, 0, 0.25}, {60, 0, 0.5}, {0, 60, 0.75}}, t));
  CHECK(t.depthsInUnit);
  REQUIRE(setup({{0, 0, 0.25}, {60, 0, 1.0}, {0, 60, 0.75}}, t));
  CHECK_FALSE(t.depthsInUnit);
  REQUIRE(setup({{0, 0, 0.0}, {60, 0, 0.5}, {0, 60, 0.75}}, t));
  CHECK_FALSE(t.depthsInUnit);
  REQUIRE(setup({{0, 0, 0.25}, {10, 0, 0.5}, {0, 10, 0.75}}, t));
  CHECK_FALSE(t.depthsInUnit);
  // A polygon offset that pushes a triangle past the far plane clears it.
  s.polygonOffset = {true, 0.0, 1e9};
  REQUIRE(setup({{0, 0, 0.25}, {60, 0, 0.5}, {0, 60, 0.75}}, t));
  CHECK_FALSE(t.depthsInUnit);
  s.polygonOffset.enabled = false;
  // Where the span loops do not read it — depth clamp on, or a 24-bit buffer — it is not worked
  // out: left false.
  s.depthClamp = true;
  REQUIRE(setup({{0, 0, 0.25}, {60, 0, 0.5}, {0, 60, 0.75}}, t));
  CHECK_FALSE(t.depthsInUnit);
  s.depthClamp = false;
  {
    const std::vector<ClipVertex> v = windowTriangles(s.viewport, {{0, 0, 0.25}, {60, 0, 0.5}, {0, 60, 0.75}});
    REQUIRE(setupTriangle(toWindow(v[0], s.viewport), toWindow(v[1], s.viewport), toWindow(v[2], s.viewport),
                          FrontFacing, s, DepthCodec{DepthFormat::Unorm24}, t));
    CHECK_FALSE(t.depthsInUnit);
  }

  // Random triangles whose depths come within 1e-15 .. 1e-3 of 0 and 1: wherever the flag is set,
  // every covered centre's depth is in (0, 1]. Some must be set, or the test shows nothing.
  TestRandom r(20261125);
  int set = 0;
  for (int i = 0; i < 4000; ++i) {
    auto depth = [&] {
      const double gap = std::pow(10.0, r.uniform(-15.0, -3.0));
      switch (r.below(3)) {
        case 0: return gap;
        case 1: return 1.0 - gap;
        default: return r.uniform(0.0, 1.0);
      }
    };
    s.polygonOffset = {r.below(4) == 0, r.uniform(-1.0, 1.0), double(r.below(9)) - 4.0};
    const double cx = r.uniform(0.0, 64.0), cy = r.uniform(0.0, 64.0), size = r.uniform(8.0, 80.0);
    auto point = [&] { return glm::dvec3(cx + r.uniform(-size, size), cy + r.uniform(-size, size), depth()); };
    if (!setup({point(), point(), point()}, t) || !t.depthsInUnit) continue;
    ++set;
    rasterizeTriangle(t, Rect{0, 0, 64, 64}, [&](int x, int y, int64_t, int64_t, int64_t) {
      const double z = planeDepthAt(t, x, y) + t.depthOffset;
      if (!(z > 0.0 && z <= 1.0)) FAIL("pixel " << x << "," << y << " of triangle " << i << " has depth " << z);
    });
  }
  CHECK(set > 200);
}

TEST_CASE("edgeAt is the edge function of the vertices at the pixel centre, for vertices across the guard band",
          "[raster][setup][edges]") {
  // The definition evaluated from the vertices in 128-bit integers (no overflow whatever the
  // inputs), against edgeAt's 64-bit arithmetic, at pixels inside a large framebuffer: the span
  // loops and the coverage tests' oracle both start from edgeAt.
  TestRandom random(0x2545F4914F6CDD1Dull);
  auto next = [&]() { return random.bits(); };
  __extension__ typedef __int128 Wide;  // GCC's, wide enough for any product of two int64 here
  const int64_t reach = int64_t(1) << 27;  // sub-pixels: 2^19 pixels, beyond any guard band here
  RenderState rs;
  const DepthCodec codec;
  int checked = 0;
  for (int n = 0; n < 2000; ++n) {
    WindowVertex v[3];
    for (WindowVertex& w : v) {
      const int64_t spread = n % 2 ? reach : 4096 * kSubpixelOne;
      w.x = int64_t(next() % uint64_t(2 * spread)) - spread;
      w.y = int64_t(next() % uint64_t(2 * spread)) - spread;
      w.fx = double(w.x) / kSubpixelOne;
      w.fy = double(w.y) / kSubpixelOne;
    }
    TriangleSetup t;
    if (!setupTriangle(v[0], v[1], v[2], FrontFacing, rs, codec, t)) continue;
    for (int k = 0; k < 8; ++k) {
      const int px = int(next() % 16384) - 64, py = int(next() % 16384) - 64;
      for (int i = 0; i < 3; ++i) {
        const WindowVertex& a = t.v[(i + 1) % 3];
        const WindowVertex& b = t.v[(i + 2) % 3];
        const Wide sx = Wide(px) * kSubpixelOne + kSubpixelHalf, sy = Wide(py) * kSubpixelOne + kSubpixelHalf;
        const Wide expected = Wide(b.x - a.x) * (sy - a.y) - Wide(b.y - a.y) * (sx - a.x);
        REQUIRE(Wide(t.edgeAt(i, px, py)) == expected);
      }
    }
    ++checked;
  }
  CHECK(checked > 1900);
}

TEST_CASE("window coordinates beyond the fixed-point range saturate and their triangle is rejected", "[raster][setup]") {
  // A non-finite or huge clip position used to reach a double -> int64_t conversion whose result
  // is undefined. Now snap saturates at +-2^20 pixels (2^28 in 1/256 pixel) and set-up rejects
  // the triangle; the guard band keeps every finite clipped vertex far inside that bound.
  Framebuffer fb(64, 64);
  RenderState state;
  state.viewport = Viewport{0, 0, 64, 64, 0.0, 1.0};
  auto vertex = [](double x, double y) {
    ClipVertex v;
    v.position = glm::dvec4(x, y, 0.0, 1.0);
    return v;
  };
  const ClipVertex a = vertex(-0.5, -0.5), b = vertex(0.5, -0.5), c = vertex(0.0, 0.5);
  const WindowVertex wa = toWindow(a, state.viewport), wb = toWindow(b, state.viewport);
  TriangleSetup t;
  CHECK(setupTriangle(wa, wb, toWindow(c, state.viewport), FrontFacing, state, fb.depthCodec(), t));
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  for (const double x : {nan, inf, -inf, 1e300, -1e300, 1e7}) {
    CAPTURE(x);
    const ClipVertex bad = vertex(x, 0.25);
    const WindowVertex w = toWindow(bad, state.viewport);
    CHECK(std::llabs(w.x) == (int64_t(1) << 28));
    CHECK(w.y == 40 * 256);  // y_ndc 0.25 on 64 pixels: (0.25 + 1) * 32 = 40, exact
    CHECK_FALSE(setupTriangle(wa, wb, w, FrontFacing, state, fb.depthCodec(), t));
  }
  // Through the renderer: a triangle with a NaN vertex covers nothing, and nothing is undefined.
  Framebuffer counted(8, 8);
  RenderState s = coverageCountingState(counted);
  std::vector<ClipVertex> v = windowTriangles(s.viewport, {{1, 1, 0.5}, {7, 1, 0.5}, {1, 7, 0.5}});
  v[2].position.x = nan;
  Renderer r(counted);
  draw(r, s, v);
  int covered = 0;
  for (uint8_t cell : counted.stencil()) covered += cell;
  CHECK(covered == 0);
}
