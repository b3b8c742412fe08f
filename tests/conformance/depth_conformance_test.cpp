// Depth test, depth mask, polygon offset and depth clamp against Mesa, in shadowref's 24-bit depth
// mode.
#include <iostream>

#include "conformance/case_builder.h"
#include "trace/osmesa/osmesa_replay.h"

using namespace shadowref;
using namespace shadowref::conformance;

namespace {

constexpr int kSize = 64;

// A sloped reference triangle pair written with ALWAYS, then crossing triangles tested with
// `func`; the crossing makes the depth comparison go both ways inside each triangle.
Scenario depthFuncScenario(CompareFunc func, bool depthWrite) {
  Scenario sc;
  sc.name = std::string("depth func ") + name(func) + (depthWrite ? "" : ", depth mask off");
  sc.width = sc.height = kSize;
  DrawStep ref;
  ref.state = fullViewportState(kSize, kSize);
  ref.state.depthTest = true;
  ref.state.depthFunc = CompareFunc::Always;
  // Shared diagonal moved off the pixel centres (x + y = 64.25).
  addTriangle(ref, {0, 0.25, -0.5}, {64, 0.25, 0.5}, {0, 64.25, -0.5}, {0.2, 0.4, 0.6, 1});
  addTriangle(ref, {64, 0.25, 0.5}, {64, 64.25, 0.5}, {0, 64.25, -0.5}, {0.6, 0.4, 0.2, 1});
  sc.steps.push_back(ref);
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.depthTest = true;
  d.state.depthFunc = func;
  d.state.depthWrite = depthWrite;
  d.state.stencilTest = true;  // count the depth results: dpfail -> +1, dppass -> +2 (see stencil)
  for (StencilFaceState& s : d.state.stencil) {
    s.dpfail = StencilOp::Incr;
    s.dppass = StencilOp::Invert;
  }
  // Off the pixel-centre lattice by (3/256, 5/256): no fill-rule ties here (those are §Ties).
  const double ox = 3.0 / 256, oy = 5.0 / 256;
  addTriangle(d, {2 + ox, 60 + oy, 0.5}, {8 + ox, 3 + oy, -0.6}, {61 + ox, 30 + oy, 0.1}, {1, 0, 0, 1});
  addTriangle(d, {30 + ox, 2 + oy, 0.3}, {62 + ox, 62 + oy, -0.4}, {3 + ox, 40 + oy, 0.0}, {0, 1, 0, 1});
  // The same plane as the reference: EQUAL, LEQUAL, GEQUAL see exact ties here.
  addTriangle(d, {10 + ox, 10 + oy, -0.5 + (10 + ox) / 64}, {50 + ox, 12 + oy, -0.5 + (50 + ox) / 64},
              {20 + ox, 40 + oy, -0.5 + (20 + ox) / 64}, {0, 0, 1, 1});
  sc.steps.push_back(d);
  return sc;
}

}  // namespace

TEST_CASE("each depth func and the depth mask decide as in Mesa", "[conformance][depth]") {
  for (CompareFunc func : {CompareFunc::Never, CompareFunc::Less, CompareFunc::Equal, CompareFunc::LEqual,
                           CompareFunc::Greater, CompareFunc::NotEqual, CompareFunc::GEqual, CompareFunc::Always})
    checkAgreement(runCase(depthFuncScenario(func, true)));
  checkAgreement(runCase(depthFuncScenario(CompareFunc::Less, false)));
}

namespace {

Scenario polygonOffsetScenario(double factor, double units, double zSlope) {
  Scenario sc;
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "polygon offset factor %g units %g, slope %g/px", factor, units, zSlope);
  sc.name = buffer;
  sc.width = sc.height = kSize;
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.depthTest = true;
  d.state.depthFunc = CompareFunc::Always;
  d.state.polygonOffset = PolygonOffset{true, factor, units};
  // NDC z changes by 2 * zSlope per pixel in x, so window depth by zSlope per pixel.
  const double z0 = -0.2;
  addTriangle(d, {0, 0, z0}, {64, 0, z0 + 128 * zSlope}, {0, 64, z0}, {1, 1, 1, 1});
  addTriangle(d, {64, 0, z0 + 128 * zSlope}, {64, 64, z0 + 128 * zSlope}, {0, 64, z0}, {1, 1, 1, 1});
  sc.steps.push_back(d);
  return sc;
}

// Depth code at the framebuffer centre with offset minus without, in 24-bit units.
double measuredOffsetUnits(const trace::Buffers& with, const trace::Buffers& without) {
  const size_t centre = size_t(kSize / 2) * kSize + kSize / 2;
  return double(with.depth[centre]) - double(without.depth[centre]);
}

}  // namespace

TEST_CASE("polygon offset: the factor term matches Mesa, Mesa's units term is r = 2 / (2^24 - 1)",
          "[conformance][depth][offset]") {
  // The slope term factor * max(|dz/dx|, |dz/dy|) ([GL 2.1, §3.5.5]).
  for (double factor : {1.0, -2.0, 4.0}) checkAgreement(runCase(polygonOffsetScenario(factor, 0.0, 1.0 / 4096)));

  // The units term: shadowref's r for unorm24 is one code, 1 / (2^24 - 1)
  // (DepthCodec::resolvableDifference). Measure Mesa's r on a flat triangle.
  const Replayed without = replayScenario(polygonOffsetScenario(0.0, 0.0, 0.0));
  for (double units : {1.0, 5.0, -3.0}) {
    const Replayed with = replayScenario(polygonOffsetScenario(0.0, units, 0.0));
    const double ours = measuredOffsetUnits(with.shadowref, without.shadowref);
    const double mesa = measuredOffsetUnits(with.mesa, without.mesa);
    INFO("units " << units << ": shadowref moves depth by " << ours << " codes, " << trace::osmesaRenderer() << " by " << mesa);
    CHECK(ours == units);
    CHECK(mesa == 2 * units);  // gallium's draw/setup stage doubles the units term
  }
  // The combined case as a table row: the difference is exactly `units` codes, as documented.
  Scenario combined = polygonOffsetScenario(1.0, 2.0, 1.0 / 4096);
  combined.depthTolerance = 2 + 2;
  combined.note = "Mesa r = 2/(2^24-1), shadowref r = 1/(2^24-1): depth differs by `units` codes (§Polygon offset)";
  checkAgreement(runCase(combined));
}

TEST_CASE("shadowref's 24-bit depth is the exact plane depth rounded, Mesa is within 2 codes of it",
          "[conformance][depth][precision]") {
  // One triangle over the whole framebuffer (one more beyond it), window depth
  // z(x, y) = 0.3 + x / 200 + y / 300 at pixel centres: every code is known exactly.
  Scenario sc;
  sc.name = "depth precision, plane";
  sc.width = sc.height = kSize;
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.depthTest = true;
  d.state.depthFunc = CompareFunc::Always;
  auto ndc = [](double x, double y) { return 2.0 * (0.3 + x / 200 + y / 300) - 1.0; };
  addTriangle(d, {0, 0, ndc(0, 0)}, {128, 0, ndc(128, 0)}, {0, 128, ndc(0, 128)}, {1, 1, 1, 1});
  sc.steps.push_back(d);
  const Replayed replayed = replayScenario(sc);
  const trace::Buffers &ours = replayed.shadowref, &mesa = replayed.mesa;
  // Both implementations receive float clip coordinates: the exact plane is through those.
  auto window = [](double zNdc) { return double(float(zNdc)) * 0.5 + 0.5; };
  const double z0 = window(ndc(0, 0)), z1 = window(ndc(128, 0)), z2 = window(ndc(0, 128));
  double mesaWorst = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double exact = (z0 + (z1 - z0) * (x + 0.5) / 128 + (z2 - z0) * (y + 0.5) / 128) * 16777215.0;
      const size_t i = size_t(y) * kSize + size_t(x);
      INFO("pixel " << x << "," << y << " exact " << exact);
      REQUIRE(std::fabs(double(ours.depth[i]) - exact) <= 0.5 + 1e-6);
      mesaWorst = std::max(mesaWorst, std::fabs(double(mesa.depth[i]) - exact));
    }
  }
  std::cout << "depth precision: " << trace::osmesaRenderer() << " is at most " << mesaWorst
            << " codes from the exact depth\n";
  CHECK(mesaWorst < 2.0);
  checkAgreement(runCase(sc));
}

TEST_CASE("depth clamp keeps triangles beyond the near and far planes and clamps their depth as Mesa does",
          "[conformance][depth][clamp]") {
  Scenario sc;
  sc.name = "depth clamp, triangles through near and far";
  sc.width = sc.height = kSize;
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.depthTest = true;
  d.state.depthFunc = CompareFunc::LEqual;
  d.state.depthClamp = true;
  // NDC z from -1.6 to 1.5 across the triangles: both ends are clamped to the depth range.
  addTriangle(d, {0, 0, -1.6}, {64, 8, 1.5}, {10, 64, 0.2}, {1, 0, 0, 1});
  addTriangle(d, {64, 64, -1.3}, {2, 50, 1.2}, {50, 2, 0.0}, {0, 1, 0, 1});
  sc.steps.push_back(d);
  checkAgreement(runCase(sc));
}

// Regression: shadowref once interpolated depth with barycentric weights of the triangle snapped to
// 1/256 pixel while keeping the unsnapped vertex depths, so a steep triangle's depth was off by
// |grad z| * (snap displacement <= 1/512 px) — hundreds of 24-bit units. Mesa (both drivers), and
// now shadowref, evaluate the plane through the unsnapped vertices.
TEST_CASE("the depth of a steep triangle with vertices off the sub-pixel grid is the exact plane depth",
          "[conformance][depth][snapped]") {
  Scenario sc;
  sc.name = "steep plane, vertices off the 1/256 grid";
  sc.width = sc.height = kSize;
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.depthTest = true;
  d.state.depthFunc = CompareFunc::Always;
  // Window depth z = 0.1 + 0.012 x (steep: 0.012 per pixel = 201326 codes); vertex x off-grid by
  // 1/1000 px, which snapping moves by ~1/1000 px: ~200 codes of error.
  const double xs[3] = {-0.4 + 0.001, 70.0 + 0.001, -0.4 + 0.001};
  const double ys[3] = {-0.4, -0.4, 70.0};
  auto ndc = [](double x) { return 2.0 * (0.1 + 0.012 * x) - 1.0; };
  addTriangle(d, {xs[0], ys[0], ndc(xs[0])}, {xs[1], ys[1], ndc(xs[1])}, {xs[2], ys[2], ndc(xs[2])}, {1, 1, 1, 1});
  sc.steps.push_back(d);
  const trace::Buffers ours = replayScenario(sc).shadowref;
  double worst = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x + y <= 66; ++x)  // well inside the hypotenuse x + y = 69.6
      if (x < kSize) worst = std::max(worst, std::fabs(double(ours.depth[size_t(y) * kSize + size_t(x)]) -
                                        (0.1 + 0.012 * (x + 0.5)) * 16777215.0));
  INFO("shadowref is up to " << worst << " codes from the exact plane depth");
  CHECK(worst <= 2.0);  // float rounding of the vertex depths allows a little more than 0.5
  checkAgreement(runCase(sc));
}
