// The fragment stage (gl/fragment_stage.h): depth at a pixel centre from the depth plane, with
// polygon offset and depth clamp, and perspective-correct varyings, against values worked by hand.
#include <catch2/catch.hpp>

#include "gl/fragment_stage.h"
#include "gl/stage_fixtures.h"

using namespace shadowref;
using namespace shadowref::testing;

TEST_CASE("fragment depth: the plane through the vertices at the pixel centre", "[gl][fragment_stage]") {
  // z = 0.2 at (0,0), 0.6 at (4,0), 0.4 at (0,4): z(x, y) = 0.2 + 0.1 x + 0.05 y. At the centre of
  // pixel (1, 2), (1.5, 2.5): 0.2 + 0.15 + 0.125 = 0.475.
  RenderState state;
  const TriangleSetup t = setupOf(windowAt(0, 0, 0.2), windowAt(4, 0, 0.6), windowAt(0, 4, 0.4), state);
  CHECK(fragmentDepth(t, 1, 2, state) == Approx(0.475).margin(1e-15));

  SECTION("polygon offset adds factor * max(|dz/dx|, |dz/dy|)") {
    state.polygonOffset = {true, 2.0, 0.0};  // 2 * 0.1
    const TriangleSetup o = setupOf(windowAt(0, 0, 0.2), windowAt(4, 0, 0.6), windowAt(0, 4, 0.4), state);
    CHECK(fragmentDepth(o, 1, 2, state) == Approx(0.675).margin(1e-15));
  }
  SECTION("depth clamp clamps to the depth range, reversed or not") {
    state.depthClamp = true;
    state.viewport.nearVal = 0.45;
    state.viewport.farVal = 0.3;
    CHECK(fragmentDepth(t, 1, 2, state) == 0.45);
    CHECK(fragmentDepth(t, 0, 0, state) == 0.3);  // 0.2 + 0.05 + 0.025 = 0.275, clamped
  }
}

TEST_CASE("varyings are interpolated perspective-correctly", "[gl][fragment_stage]") {
  // Vertices at w = 1, 2, 4 carrying 0, 1, 0. With edge values (2, 1, 1) — screen-space weights
  // 1/2, 1/4, 1/4 — the weights divided by w are 2, 1/2, 1/4 (times area2), so the value is
  // (1/2) / (2 + 1/2 + 1/4) = 2/11, not the screen-linear 1/4.
  ClipVertex a, b, c;
  b.varyings[0] = 1.0;
  a.varyings[1] = c.varyings[1] = 3.0;  // a varying equal at every vertex stays itself
  b.varyings[1] = 3.0;
  const TriangleSetup t = setupOf(windowAt(0, 0, 0.5, 1.0, &a), windowAt(4, 0, 0.5, 0.5, &b), windowAt(0, 4, 0.5, 0.25, &c));
  REQUIRE(t.area2 > 0);
  double out[2];
  interpolateVaryings(t, 2, 1, 1, 2, out);
  CHECK(out[0] == Approx(2.0 / 11.0).margin(1e-15));
  CHECK(out[1] == 3.0);
}

TEST_CASE("the shader sees the fragment's pixel, depth, facing and varyings", "[gl][fragment_stage]") {
  ClipVertex a, b, c;
  for (ClipVertex* v : {&a, &b, &c}) v->varyings = {0.25, 0.5, 0.75, 1.0};
  const TriangleSetup t = setupOf(windowAt(0, 0, 0.5, 1.0, &a), windowAt(4, 0, 0.5, 1.0, &b), windowAt(0, 4, 0.5, 1.0, &c));
  const ColorVaryingShader shader;
  const glm::dvec4 color = shadeFragment(shader, t, 1, 1, 0.5, 1, 1, 1);
  CHECK(color == glm::dvec4(0.25, 0.5, 0.75, 1.0));
}
