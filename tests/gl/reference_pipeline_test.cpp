// The reference pipeline end to end (gl/reference_pipeline.h) on draws whose every byte and
// counter is worked out by hand; the fast executor's agreement with it on random streams is
// tests/differential.
#include <catch2/catch.hpp>

#include <vector>

#include "gl/pipeline.h"
#include "gl/reference_pipeline.h"

using namespace shadowref;

namespace {
ClipVertex at(double x, double y, double z) {
  ClipVertex v;
  v.position = glm::dvec4(x, y, z, 1.0);
  return v;
}
}  // namespace

TEST_CASE("makePipeline makes the reference, one thread, and the same kind for another framebuffer",
          "[gl][reference_pipeline]") {
  Framebuffer fb(4, 4), other(2, 2);
  const std::unique_ptr<Pipeline> p = makePipeline(PipelineKind::Reference, fb, 8);
  REQUIRE(p);
  CHECK(p->kind() == PipelineKind::Reference);
  CHECK(p->threads() == 1);
  const std::unique_ptr<Pipeline> q = p->forFramebuffer(other);
  CHECK(q->kind() == PipelineKind::Reference);
  CHECK(&q->framebuffer() == &other);
}

TEST_CASE("the reference draws a quad over the viewport, then a z-fail volume side", "[gl][reference_pipeline]") {
  // 4x4 pixels. Pass 1: a quad at NDC z 0 (window depth 0.5) over the whole viewport, constant
  // colour, depth test LESS against the cleared 1.0: all 16 fragments pass and write.
  Framebuffer fb(4, 4);
  ReferencePipeline pipeline(fb);
  RenderState state;
  state.viewport = {0, 0, 4, 4, 0.0, 1.0};
  state.depthTest = true;
  ClearRequest clear;
  clear.depth = 1.0;
  clear.stencil = 0;
  pipeline.clear(clear);
  const std::vector<ClipVertex> quad = {at(-1, -1, 0), at(1, -1, 0), at(1, 1, 0), at(-1, -1, 0), at(1, 1, 0), at(-1, 1, 0)};
  const ConstantColorShader red(glm::dvec4(1, 0, 0, 1));
  pipeline.draw(DrawCall{&state, quad, {}, &red, 1});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      CHECK(fb.colorAt(x, y) == glm::vec4(1, 0, 0, 1));
      CHECK(fb.depthAt(x, y) == 0.5);
    }
  CHECK(pipeline.stats().drawCalls == 1);
  CHECK(pipeline.stats().trianglesIn == 2);
  CHECK(pipeline.stats().trianglesRasterized == 2);
  CHECK(pipeline.stats().fragments == 16);  // the shared diagonal counted once
  CHECK(pipeline.stats().colorWrites == 16);

  // Pass 2: the left half (x < 0 in NDC) behind it at window depth 0.75, no colour, depth write
  // off, stencil ALWAYS with dpfail DECR_WRAP: the 8 fragments fail the depth test and each
  // stencil byte there goes 0 -> 255; the right half stays 0.
  RenderState volume = state;
  volume.depthWrite = false;
  volume.stencilTest = true;
  volume.stencil[FrontFacing].dpfail = StencilOp::DecrWrap;
  volume.stencil[BackFacing].dpfail = StencilOp::DecrWrap;
  const std::vector<ClipVertex> half = {at(-1, -1, 0.5), at(0, -1, 0.5), at(0, 1, 0.5), at(-1, -1, 0.5), at(0, 1, 0.5), at(-1, 1, 0.5)};
  pipeline.draw(DrawCall{&volume, half, {}, nullptr, 2});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) CHECK(int(fb.stencilAt(x, y)) == (x < 2 ? 255 : 0));
  CHECK(pipeline.stats().depthFailed == 8);
  CHECK(pipeline.stats().stencilWrites == 8);
  CHECK(fb.depthAt(0, 0) == 0.5);
}
