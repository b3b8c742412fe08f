// glClear semantics (GL 2.1 §4.2.3): clear values clamped to the buffer's range, the scissor box
// limits the clear, colour mask / depth mask / stencil write mask apply.
#include <vector>

#include <catch2/catch.hpp>

#include "raster/clear.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

TEST_CASE("clears fill the whole buffer with the clamped clear value", "[raster][clear]") {
  Framebuffer fb(3, 2);
  const RenderState s = fullViewportState(fb);
  clearColor(fb, s, {1.5f, -0.5f, 0.25f, 1.0f});
  clearDepth(fb, s, 2.0);
  clearStencil(fb, s, 0x1A5);  // masked to the 8 stencil bits: 0xA5
  clearAccum(fb, s, {-3.0f, 0.5f, 2.0f, -0.25f});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      CHECK(fb.colorAt(x, y) == glm::vec4(1.0f, 0.0f, 0.25f, 1.0f));
      CHECK(fb.depthAt(x, y) == 1.0);
      CHECK(int(fb.stencilAt(x, y)) == 0xA5);
      CHECK(fb.accumAt(x, y) == glm::vec4(-1.0f, 0.5f, 1.0f, -0.25f));
    }
}

TEST_CASE("clear with scissor touches only the scissor box, in every buffer", "[raster][clear][scissor]") {
  Framebuffer fb(6, 4);
  RenderState s = fullViewportState(fb);
  clearStencil(fb, s, 1);
  clearDepth(fb, s, 1.0);
  clearColor(fb, s, glm::vec4(0.0f));
  s.scissorTest = true;
  s.scissor = {1, 1, 3, 2};
  clearStencil(fb, s, 7);
  clearDepth(fb, s, 0.25);
  clearColor(fb, s, glm::vec4(1.0f));
  CHECK(stencilPicture(fb) == rows({"111111",
                                    "177711",
                                    "177711",
                                    "111111"}));
  CHECK(picture(6, 4, [&](int x, int y) { return fb.depthAt(x, y) == 0.25 ? 'z' : '.'; }) ==
        rows({"......", ".zzz..", ".zzz..", "......"}));
  CHECK(picture(6, 4, [&](int x, int y) { return fb.colorAt(x, y) == glm::vec4(1.0f) ? '#' : '.'; }) ==
        rows({"......", ".###..", ".###..", "......"}));
}

TEST_CASE("clear respects colour mask, depth mask and the stencil write mask", "[raster][clear]") {
  Framebuffer fb(2, 1);
  RenderState s = fullViewportState(fb);
  clearColor(fb, s, {0.25f, 0.25f, 0.25f, 0.25f});
  clearDepth(fb, s, 0.5);
  clearStencil(fb, s, 0xAA);
  s.colorMask = {false, true, true, false};
  s.depthWrite = false;
  s.stencil[FrontFacing].writeMask = 0x0F;
  clearColor(fb, s, {1.0f, 0.75f, 0.5f, 1.0f});
  clearDepth(fb, s, 1.0);
  clearStencil(fb, s, 0x55);
  CHECK(fb.colorAt(1, 0) == glm::vec4(0.25f, 0.75f, 0.5f, 0.25f));
  CHECK(fb.depthAt(1, 0) == 0.5);
  CHECK(int(fb.stencilAt(1, 0)) == 0xA5);  // (0xAA & 0xF0) | (0x55 & 0x0F)
}
