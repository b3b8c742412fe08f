// Homogeneous clipping ([GL 2.1, §2.12]): near plane, points at infinity under P_inf
// ([Kuhn 2016, §3.3]), triangles behind the eye, huge coordinates, depth clamp. Each expectation is
// derived by hand in eye or window space and compared with the rasterized stencil and depth.
#include <algorithm>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/clipper.h"
#include "gl/projection.h"
#include "exec/renderer.h"
#include "support/polygon_geometry.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

std::vector<ClipVertex> project(const glm::dmat4& p, std::initializer_list<glm::dvec4> eyePoints) {
  std::vector<ClipVertex> out;
  for (const glm::dvec4& e : eyePoints) {
    ClipVertex v;
    v.position = p * e;
    out.push_back(v);
  }
  return out;
}

// Counts coverage of `triangles` (depth test ALWAYS, depth written) on a size x size target.
Framebuffer countCoverage(const std::vector<ClipVertex>& triangles, int size, RenderState base = {}) {
  Framebuffer fb(size, size);
  RenderState s = coverageCountingState(fb);
  s.depthClamp = base.depthClamp;
  s.clipFar = base.clipFar;
  s.depthTest = true;
  s.depthFunc = CompareFunc::Always;
  Renderer r(fb);
  draw(r, s, triangles);
  return fb;
}

int coveredCount(const Framebuffer& fb) {
  int n = 0;
  for (uint8_t c : fb.stencil()) n += c;
  return n;
}

}  // namespace

TEST_CASE("a triangle crossing the near plane covers its clipped polygon", "[raster][clip]") {
  // Eye space: A (0, 0, 1) is behind the eye (w = -1), B (-3, -3, -3), C (3, -1, -2); near = 1.
  // AB meets z = -1 at t = 1/2: (-1.5, -1.5, -1) -> NDC (-1.5, -1.5) -> window (-8, -8).
  // CA meets z = -1 at t = 2/3 from A: (2, -2/3, -1) -> NDC (2, -2/3) -> window (48, 16/3).
  // B -> NDC (-1, -1) -> (0, 0); C -> NDC (1.5, -0.5) -> (40, 8). 32x32 viewport.
  const Polygon2 clipped{{-8, -8}, {0, 0}, {40, 8}, {48, 16.0 / 3.0}};
  const glm::dvec4 a(0, 0, 1, 1), b(-3, -3, -3, 1), c(3, -1, -2, 1);
  SECTION("glFrustum") { requireCoverage(countCoverage(project(frustum(-1, 1, -1, 1, 1, 100), {a, b, c}), 32), clipped); }
  SECTION("P_inf") {
    RenderState s;
    s.clipFar = false;
    requireCoverage(countCoverage(project(infiniteFrustum(-1, 1, -1, 1, 1), {a, b, c}), 32, s), clipped);
  }
  SECTION("clockwise") { requireCoverage(countCoverage(project(frustum(-1, 1, -1, 1, 1, 100), {a, c, b}), 32), clipped); }
}

TEST_CASE("P_inf: a shadow-volume side quad extruded to infinity covers its trapezoid, depth 1 at infinity",
          "[raster][clip][pinf]") {
  // A (-1, -1, -2, 1), B (1, -1, -2, 1) and the points at infinity C (1, 1/32, -1, 0), D (-1, 1/32, -1, 0).
  // P_inf (near 1): clip = (x, y, -z - 2w, -z). A -> (-1, -1, 0, 2): NDC (-0.5, -0.5, 0), window (8, 8),
  // depth 0.5; B -> (24, 8); C -> (1, 1/32, 1, 1): NDC z = 1 exactly, window (32, 16.5), depth 1;
  // D -> (0, 16.5). Window depth is affine in window y: 0.5 + 0.5 (y - 8) / 8.5.
  RenderState s;
  s.clipFar = false;
  const std::vector<ClipVertex> quad = project(infiniteFrustum(-1, 1, -1, 1, 1),
                                               {{-1, -1, -2, 1}, {1, -1, -2, 1}, {1, 1.0 / 32, -1, 0},
                                                {-1, -1, -2, 1}, {1, 1.0 / 32, -1, 0}, {-1, 1.0 / 32, -1, 0}});
  const Framebuffer fb = countCoverage(quad, 32, s);
  requireCoverage(fb, {{8, 8}, {24, 8}, {32, 16.5}, {0, 16.5}});
  // Row 16 has its centres on the top edge y = 16.5 (included): all 32 pixels, at depth 1.
  for (int x = 0; x < 32; ++x) {
    INFO("pixel " << x << ",16");
    CHECK(fb.stencilAt(x, 16) == 1);
    CHECK(fb.depthAt(x, 16) == Approx(1.0).margin(0x1.0p-24).epsilon(0));
  }
  CHECK(coveredCount(fb) - 32 == [] {
    int n = 0;  // rows 8..15: centres strictly inside the trapezoid, hand-counted per row below
    for (int y = 8; y <= 15; ++y) {
      const double py = y + 0.5, half = 8.0 + 8.0 * (py - 8.0) / 8.5;  // half-width about x = 16
      for (int x = 0; x < 32; ++x) n += std::abs(x + 0.5 - 16.0) < half;
    }
    return n;
  }());
  for (int y = 8; y <= 15; ++y) {
    INFO("row " << y);
    CHECK(fb.depthAt(16, y) == Approx(0.5 + 0.5 * (y + 0.5 - 8.0) / 8.5).margin(0x1.0p-23).epsilon(0));
  }
}

TEST_CASE("P_inf: a quad extruded sideways (clip w = 0) covers the half-strip up to the viewport edge",
          "[raster][clip][pinf]") {
  // A (0.5, -1, -2, 1), B (0.5, 1, -2, 1), and the direction (1, 0, 0, 0), whose clip position
  // (1, 0, 0, 0) has w = 0. The covered set is the half-strip x >= 0.5, |y| <= 1 at z = -2:
  // NDC x >= 0.25, |y| <= 0.5 -> window x >= 20, 8 <= y <= 24, all at NDC z = 0 (depth 0.5).
  RenderState s;
  s.clipFar = false;
  const std::vector<ClipVertex> tri =
      project(infiniteFrustum(-1, 1, -1, 1, 1), {{0.5, -1, -2, 1}, {0.5, 1, -2, 1}, {1, 0, 0, 0}});
  REQUIRE(tri[2].position == glm::dvec4(1, 0, 0, 0));
  const Framebuffer fb = countCoverage(tri, 32, s);
  CHECK(stencilPicture(fb) == picture(32, 32, [](int x, int y) { return x >= 20 && y >= 8 && y < 24 ? '1' : '.'; }));
  for (int y = 8; y < 24; ++y)
    for (int x = 20; x < 32; ++x) CHECK(fb.depthAt(x, y) == 0.5);
}

TEST_CASE("triangles entirely behind the eye draw nothing, with or without depth clamp", "[raster][clip]") {
  const glm::dmat4 pInf = infiniteFrustum(-1, 1, -1, 1, 1);
  // Eye z > 0: every w < 0.
  const std::vector<ClipVertex> behind = project(pInf, {{-1, -1, 2, 1}, {1, -1, 2, 1}, {0, 1, 3, 1}});
  // The negation of a visible triangle: same NDC after the divide, but w < 0.
  std::vector<ClipVertex> negated = project(pInf, {{-1, -1, -2, 1}, {1, -1, -2, 1}, {0, 1, -3, 1}});
  for (ClipVertex& v : negated) v.position = -v.position;
  for (bool clamp : {false, true}) {
    INFO("depth clamp " << clamp);
    RenderState s;
    s.clipFar = false;
    s.depthClamp = clamp;
    CHECK(coveredCount(countCoverage(behind, 16, s)) == 0);
    CHECK(coveredCount(countCoverage(negated, 16, s)) == 0);
  }
  // The un-negated triangle is visible: the test above can fail.
  std::vector<ClipVertex> visible = negated;
  for (ClipVertex& v : visible) v.position = -v.position;
  CHECK(coveredCount(countCoverage(visible, 16)) > 0);
}

TEST_CASE("triangles with coordinates of 1e20 cover the whole viewport once at the right depth",
          "[raster][clip]") {
  // NDC (-1e20, -1e20), (3e20, -1e20), (-1e20, 3e20) contain the viewport; z_ndc 0.25 -> depth 0.625.
  auto tri = [](double w) {
    std::vector<ClipVertex> v(3);
    v[0].position = glm::dvec4(-1e20 * w, -1e20 * w, 0.25 * w, w);
    v[1].position = glm::dvec4(3e20 * w, -1e20 * w, 0.25 * w, w);
    v[2].position = glm::dvec4(-1e20 * w, 3e20 * w, 0.25 * w, w);
    return v;
  };
  const std::string all = picture(32, 32, [](int, int) { return '1'; });
  for (double w : {1.0, 1e-20, 1e20}) {
    INFO("w " << w);
    const Framebuffer fb = countCoverage(tri(w), 32);
    CHECK(stencilPicture(fb) == all);
    CHECK(fb.depthAt(0, 0) == 0.625);
    CHECK(fb.depthAt(31, 31) == 0.625);
    CHECK(fb.depthAt(13, 20) == 0.625);
  }
  // A quad of two such triangles whose shared diagonal runs through pixel centres: still once each.
  std::vector<ClipVertex> quad(6);
  const glm::dvec4 p00(-1e20, -1e20, 0, 1), p10(1e20, -1e20, 0, 1), p11(1e20, 1e20, 0, 1), p01(-1e20, 1e20, 0, 1);
  quad[0].position = p00, quad[1].position = p10, quad[2].position = p11;
  quad[3].position = p00, quad[4].position = p11, quad[5].position = p01;
  CHECK(stencilPicture(countCoverage(quad, 32)) == all);
}

TEST_CASE("a triangle with a vertex in view and two at 1e20 covers the cone between its edges", "[raster][clip]") {
  // Near vertex at NDC (0.3, -0.2) = window (20.8, 12.8); far vertices in the directions (1, 0.3)
  // and (-0.2, 1) from it, 1e20 away. Each edge through the viewport is fixed by the near vertex and
  // a direction known to 1e-16, so its window position is well conditioned. (An edge between two
  // vertices at 1e20 is not: a relative change of 1e-16 in one vertex moves it by 1e4 NDC units.)
  const glm::dvec2 near(0.3, -0.2), d1(1.0, 0.3), d2(-0.2, 1.0);
  std::vector<ClipVertex> tri(3);
  tri[0].position = glm::dvec4(near, 0.0, 1.0);
  tri[1].position = glm::dvec4(near + 1e20 * d1, 0.0, 1.0);
  tri[2].position = glm::dvec4(near + 1e20 * d2, 0.0, 1.0);
  const glm::dvec2 w = (near + 1.0) * 16.0;  // window position of the near vertex
  const Polygon2 cone{w, w + 1e6 * d1, w + 1e6 * d2};
  requireCoverage(countCoverage(tri, 32), cone);
  std::swap(tri[1], tri[2]);
  requireCoverage(countCoverage(tri, 32), cone);
}

TEST_CASE("depth clamp: geometry in front of the near plane is kept and its depth clamped to 0",
          "[raster][clip][clamp]") {
  // glFrustum(-1, 1, -1, 1, 1, 10), 32x32. The floor y = -0.25, x in [-40, 40], z from -0.5 to -20
  // projects to y_ndc = 0.25 / z. Without depth clamp it is cut at z = -1 and z = -10:
  // y_ndc in [-0.25, -0.025] -> window rows [12, 15.6]. With depth clamp all of it stays:
  // y_ndc in [-0.5, -0.0125] -> window rows [8, 15.8], depth clamp(window depth, 0, 1).
  const double n = 1, f = 10;
  const std::vector<ClipVertex> floor = project(frustum(-1, 1, -1, 1, n, f),
                                                {{-40, -0.25, -0.5, 1}, {40, -0.25, -0.5, 1}, {40, -0.25, -20, 1},
                                                 {-40, -0.25, -0.5, 1}, {40, -0.25, -20, 1}, {-40, -0.25, -20, 1}});
  auto windowDepth = [&](int row) {
    const double yNdc = (row + 0.5) / 16.0 - 1.0;
    const double z = 0.25 / yNdc;  // eye z of the floor seen through this row
    const double zNdc = (-(f + n) / (f - n) * z - 2.0 * f * n / (f - n)) / -z;
    return 0.5 * (zNdc + 1.0);
  };
  for (bool clamp : {false, true}) {
    INFO("depth clamp " << clamp);
    RenderState s;
    s.depthClamp = clamp;
    const Framebuffer fb = countCoverage(floor, 32, s);
    const int firstRow = clamp ? 8 : 12;
    CHECK(stencilPicture(fb) ==
          picture(32, 32, [&](int, int y) { return y >= firstRow && y <= 15 ? '1' : '.'; }));
    for (int y = firstRow; y <= 15; ++y) {
      INFO("row " << y << " analytic depth " << windowDepth(y));
      const double expected = std::clamp(windowDepth(y), 0.0, 1.0);
      CHECK(fb.depthAt(5, y) == Approx(expected).margin(0x1.0p-23).epsilon(0));
      if (y < 12) CHECK(fb.depthAt(5, y) == 0.0);
    }
  }
}

TEST_CASE("clipPolygon cuts a shared edge at the same point from both of its triangles", "[raster][clip]") {
  // Edge PQ crosses the near plane; triangles (P, Q, R) and (Q, P, S) list it in opposite directions.
  ClipVertex p, q, r, s;
  p.position = {0.3, -0.7, -3.1, 0.9};   // outside: z < -w
  q.position = {-0.2, 0.4, 1.3, 2.7};    // inside
  r.position = {0.9, 0.8, 0.5, 1.5};
  s.position = {-1.1, -0.9, 0.1, 1.2};
  ClipPlanes planes;
  std::vector<ClipVertex> out1, out2, scratch;
  clipPolygon({p, q, r}, planes, 0, out1, scratch);
  clipPolygon({q, p, s}, planes, 0, out2, scratch);
  auto onNear = [](const std::vector<ClipVertex>& poly) {
    std::vector<glm::dvec4> pts;
    for (const ClipVertex& v : poly)
      if (v.position.z == -v.position.w || std::abs(v.position.z + v.position.w) < 1e-12) pts.push_back(v.position);
    return pts;
  };
  const auto a = onNear(out1), b = onNear(out2);
  REQUIRE(a.size() == 2);
  REQUIRE(b.size() == 2);
  // The cut of PQ is the one point both polygons share (bit-identical).
  int shared = 0;
  for (const glm::dvec4& x : a)
    for (const glm::dvec4& y : b) shared += x == y;
  CHECK(shared == 1);
}

TEST_CASE("watertight through the near plane: a jittered floor grid reaching behind the eye", "[raster][clip][watertight]") {
  // The floor y = -1, x in [-60, 60], z in [-50, 5] (the eye at the origin looks down -z), split into
  // jittered cells whose triangles cross the near plane and w = 0. With a 90 degree frustum
  // (+-0.5 at near 0.5), clip x = x, y = y, w = -z. Its far edge z = -50 projects to
  // y_ndc = -1/50, window y = 0.98 * 32 = 31.36 on a 64x64 viewport; its sides stay outside the
  // viewport (|x_ndc| >= 60/50); the near part projects below it. So rows 0..30 are covered once.
  const int nx = 16, nz = 14;
  for (int projection = 0; projection < 2; ++projection) {
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      INFO((projection == 0 ? "glFrustum" : "P_inf") << ", seed " << seed);
      const glm::dmat4 p = projection == 0 ? frustum(-0.5, 0.5, -0.5, 0.5, 0.5, 100)
                                          : infiniteFrustum(-0.5, 0.5, -0.5, 0.5, 0.5);
      TestRandom rng(seed);
      std::vector<ClipVertex> vertices;
      for (int j = 0; j <= nz; ++j)
        for (int i = 0; i <= nx; ++i) {
          double x = -60.0 + 120.0 * i / nx, z = -50.0 + 55.0 * j / nz;
          if (i > 0 && i < nx) x += rng.uniform(-2.5, 2.5);  // boundary nodes stay on their lines
          if (j > 0 && j < nz) z += rng.uniform(-1.2, 1.2);
          ClipVertex v;
          v.position = p * glm::dvec4(x, -1.0, z, 1.0);
          vertices.push_back(v);
        }
      const std::vector<uint32_t> indices = gridTriangles(nx, nz, Winding::Mixed, rng);  // both windings in one mesh
      Framebuffer fb(64, 64);
      RenderState s = coverageCountingState(fb);
      s.clipFar = projection == 0;
      Renderer r(fb);
      DrawCall call;
      call.state = &s;
      call.vertices = vertices;
      call.indices = indices;
      r.draw(call);
      CHECK(stencilPicture(fb) == picture(64, 64, [](int, int y) { return y <= 30 ? '1' : '.'; }));
    }
  }
}
