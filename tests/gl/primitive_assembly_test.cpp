// Primitive assembly (gl/primitive_assembly.h): the draw region, the canonical rotation, and how a
// triangle is counted — passed whole, clipped into a fan, culled — with counts worked by hand.
#include <catch2/catch.hpp>

#include "gl/primitive_assembly.h"

using namespace shadowref;

namespace {
ClipVertex at(double x, double y, double z = 0.0, double w = 1.0) {
  ClipVertex v;
  v.position = glm::dvec4(x, y, z, w);
  return v;
}
}  // namespace

TEST_CASE("the draw region is viewport, framebuffer and scissor intersected", "[gl][primitive_assembly]") {
  const Framebuffer fb(10, 8);
  RenderState state;
  state.viewport = {-2, 3, 20, 20, 0.0, 1.0};
  Rect r = drawRegion(state, fb);
  CHECK((r.x == 0 && r.y == 3 && r.width == 10 && r.height == 5));
  state.scissorTest = true;
  state.scissor = {4, 0, 3, 5};
  r = drawRegion(state, fb);
  CHECK((r.x == 4 && r.y == 3 && r.width == 3 && r.height == 2));
  state.scissor = {20, 0, 3, 5};
  CHECK(drawRegion(state, fb).width == 0);
}

TEST_CASE("the canonical rotation starts at the smallest vertex and keeps the winding", "[gl][primitive_assembly]") {
  const ClipVertex a = at(1, 0), b = at(0, 5), c = at(0, 2);
  const ClipVertex *p = &a, *q = &b, *r = &c;
  canonicalRotation(p, q, r);
  // Smallest: c (x 0, y 2 < 5); the cycle a -> b -> c continues c -> a -> b.
  CHECK(p == &c);
  CHECK(q == &a);
  CHECK(r == &b);
}

TEST_CASE("assembly counts a triangle as passed, clipped into a fan, or culled", "[gl][primitive_assembly]") {
  RenderState state;
  state.viewport = {0, 0, 16, 16, 0.0, 1.0};
  const ClipPlanes planes = clipPlanesFor(state);
  AssemblyScratch scratch;
  std::vector<TriangleSetup> setups;
  RasterStats stats;
  const DepthCodec codec;
  auto assemble = [&](const ClipVertex& a, const ClipVertex& b, const ClipVertex& c) {
    assembleTriangle(&a, &b, &c, state, planes, 0, codec, scratch, setups, stats);
  };

  assemble(at(-0.5, -0.5), at(0.5, -0.5), at(0, 0.5));  // inside every plane
  CHECK(setups.size() == 1);
  CHECK(stats.trianglesRasterized == 1);
  CHECK(stats.trianglesClipped == 0);

  // One corner beyond the near plane (z < -w): the triangle is cut to a quadrilateral, two fan
  // triangles.
  assemble(at(-0.5, -0.5, 0.0), at(0.5, -0.5, 0.0), at(0, 0.5, -3.0));
  CHECK(setups.size() == 2);
  CHECK(stats.trianglesClipped == 1);
  CHECK(stats.trianglesRasterized == 3);

  // Every corner beyond the near plane: clipped away, counted as clipped, nothing set up.
  assemble(at(-0.5, -0.5, -2.0), at(0.5, -0.5, -2.0), at(0, 0.5, -2.0));
  CHECK(setups.empty());
  CHECK(stats.trianglesClipped == 2);
  CHECK(stats.trianglesCulled == 0);

  // Clockwise with back faces culled (front: counter-clockwise): culled.
  state.cull = CullMode::Back;
  assemble(at(-0.5, -0.5), at(0, 0.5), at(0.5, -0.5));
  CHECK(setups.empty());
  CHECK(stats.trianglesCulled == 1);

  // No area (three corners on a line): culled whatever the cull mode.
  state.cull = CullMode::None;
  assemble(at(-0.5, -0.5), at(0, 0), at(0.5, 0.5));
  CHECK(setups.empty());
  CHECK(stats.trianglesCulled == 2);
}

TEST_CASE("an index beyond the vertices is refused before anything is drawn", "[gl][primitive_assembly]") {
  const std::vector<ClipVertex> vertices(3);
  const std::vector<uint32_t> indices = {0, 1, 3};
  DrawCall call;
  call.vertices = vertices;
  call.indices = indices;
  CHECK_THROWS_AS(checkIndices(call), std::out_of_range);
  CHECK(trianglesOf(call) == 1);
}
