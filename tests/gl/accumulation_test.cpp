// glAccum ([GL 2.1, §4.2.4]; [Hempe 2004, §4.2.2]): ACCUM, LOAD, RETURN, MULT, ADD on whole pixels.
// Values are dyadic so every expected float is exact.
#include <catch2/catch.hpp>

#include "gl/accumulation.h"
#include "gl/clear.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

// Two pixels with colours c0 = (0.5, 0.25, 1, 0.5) and c1 = (0.25, 0.75, 0, 1), accumulation 0.
Framebuffer twoPixels() {
  Framebuffer fb(2, 1);
  fb.ensureColor();
  fb.color()[0] = {0.5f, 0.25f, 1.0f, 0.5f};
  fb.color()[1] = {0.25f, 0.75f, 0.0f, 1.0f};
  clearAccum(fb, fullViewportState(fb), glm::vec4(0.0f));
  return fb;
}

}  // namespace

TEST_CASE("ACCUM adds value * colour to the accumulation buffer", "[raster][accum]") {
  Framebuffer fb = twoPixels();
  const RenderState s = fullViewportState(fb);
  accumulate(fb, s, AccumOp::Accum, 0.5f);
  CHECK(fb.accumAt(0, 0) == glm::vec4(0.25f, 0.125f, 0.5f, 0.25f));
  CHECK(fb.accumAt(1, 0) == glm::vec4(0.125f, 0.375f, 0.0f, 0.5f));
  accumulate(fb, s, AccumOp::Accum, 0.25f);
  CHECK(fb.accumAt(0, 0) == glm::vec4(0.375f, 0.1875f, 0.75f, 0.375f));
}

TEST_CASE("LOAD replaces the accumulation buffer with value * colour", "[raster][accum]") {
  Framebuffer fb = twoPixels();
  const RenderState s = fullViewportState(fb);
  accumulate(fb, s, AccumOp::Accum, 0.5f);
  accumulate(fb, s, AccumOp::Load, 2.0f);
  CHECK(fb.accumAt(0, 0) == glm::vec4(1.0f, 0.5f, 2.0f, 1.0f));
  CHECK(fb.accumAt(1, 0) == glm::vec4(0.5f, 1.5f, 0.0f, 2.0f));
}

TEST_CASE("MULT scales and ADD offsets the accumulation buffer", "[raster][accum]") {
  Framebuffer fb = twoPixels();
  const RenderState s = fullViewportState(fb);
  accumulate(fb, s, AccumOp::Load, 1.0f);
  accumulate(fb, s, AccumOp::Mult, 0.5f);
  CHECK(fb.accumAt(0, 0) == glm::vec4(0.25f, 0.125f, 0.5f, 0.25f));
  accumulate(fb, s, AccumOp::Add, 0.25f);
  CHECK(fb.accumAt(0, 0) == glm::vec4(0.5f, 0.375f, 0.75f, 0.5f));
  accumulate(fb, s, AccumOp::Add, -1.0f);
  CHECK(fb.accumAt(1, 0) == glm::vec4(-0.625f, -0.375f, -0.75f, -0.25f));
  // The colour buffer is untouched by all three.
  CHECK(fb.colorAt(0, 0) == glm::vec4(0.5f, 0.25f, 1.0f, 0.5f));
}

TEST_CASE("RETURN writes value * accumulation to colour, clamped to [0, 1]", "[raster][accum]") {
  Framebuffer fb = twoPixels();
  const RenderState s = fullViewportState(fb);
  accumulate(fb, s, AccumOp::Load, 1.0f);
  accumulate(fb, s, AccumOp::Add, -0.5f);  // acc0 (0, -0.25, 0.5, 0), acc1 (-0.25, 0.25, -0.5, 0.5)
  accumulate(fb, s, AccumOp::Return, 4.0f);
  CHECK(fb.colorAt(0, 0) == glm::vec4(0.0f, 0.0f, 1.0f, 0.0f));  // -1 -> 0, 2 -> 1
  CHECK(fb.colorAt(1, 0) == glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
  // The accumulation buffer keeps its values.
  CHECK(fb.accumAt(0, 0) == glm::vec4(0.0f, -0.25f, 0.5f, 0.0f));
}

TEST_CASE("RETURN respects the colour mask and the scissor box", "[raster][accum]") {
  Framebuffer fb = twoPixels();
  RenderState s = fullViewportState(fb);
  accumulate(fb, s, AccumOp::Load, 0.5f);  // acc0 (0.25, 0.125, 0.5, 0.25)
  s.colorMask = {false, true, false, true};
  s.scissorTest = true;
  s.scissor = {0, 0, 1, 1};
  accumulate(fb, s, AccumOp::Return, 2.0f);
  CHECK(fb.colorAt(0, 0) == glm::vec4(0.5f, 0.25f, 1.0f, 0.5f));  // G, A written: 0.25, 0.5
  // Pixel 1 lies outside the scissor box: unchanged.
  CHECK(fb.colorAt(1, 0) == glm::vec4(0.25f, 0.75f, 0.0f, 1.0f));
  s.colorMask = {true, false, false, false};
  accumulate(fb, s, AccumOp::Return, 1.0f);
  CHECK(fb.colorAt(0, 0) == glm::vec4(0.25f, 0.25f, 1.0f, 0.5f));
}

TEST_CASE("16 ACCUMs of weight 1/16 then RETURN average the frames ([Hempe 2004, §4.2.2])", "[raster][accum]") {
  Framebuffer fb(1, 1);
  const RenderState s = fullViewportState(fb);
  clearAccum(fb, s, glm::vec4(0.0f));
  for (int i = 0; i < 16; ++i) {
    clearColor(fb, s, glm::vec4(i < 4 ? 1.0f : 0.0f));  // lit in 4 of 16 frames
    accumulate(fb, s, AccumOp::Accum, 1.0f / 16.0f);
  }
  accumulate(fb, s, AccumOp::Return, 1.0f);
  CHECK(fb.colorAt(0, 0) == glm::vec4(0.25f));
}
