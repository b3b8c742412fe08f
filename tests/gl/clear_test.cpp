// glClear semantics ([GL 2.1, §4.2.3]): clear values clamped to the buffer's range, the scissor box
// limits the clear, colour mask / depth mask / stencil write mask apply.
#include <functional>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/clear.h"
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

// A ParallelFor that runs the parts backwards and records them: the order must not matter, and
// a clear of many pixels must be cut into parts at all for the threads to share it.
struct RecordingParallel {
  std::vector<int> counts;
  ParallelFor fn() {
    return [this](int count, const std::function<void(int)>& task) {
      counts.push_back(count);
      for (int i = count - 1; i >= 0; --i) task(i);
    };
  }
};

TEST_CASE("a clear cut into parts for threads writes every pixel of a new buffer, and only the scissor box later",
          "[raster][clear][threads]") {
  // 517 x 300 (155 100 pixels): parts of at least 2^15 pixels, so 4 parts of 75 rows.
  Framebuffer fb(517, 300);
  RenderState s = fullViewportState(fb);
  RecordingParallel parallel;
  // New buffers are allocated unwritten and then filled part by part: every pixel must come out
  // with the clear value (the allocator's leftovers would show up here or under the sanitizers).
  clearColor(fb, s, {0.25f, 0.5f, 0.75f, 1.0f}, parallel.fn());
  clearDepth(fb, s, 0.5, parallel.fn());
  clearStencil(fb, s, 3, parallel.fn());
  clearAccum(fb, s, {-0.5f, 0.0f, 0.5f, 1.0f}, parallel.fn());
  CHECK(parallel.counts == std::vector<int>{4, 4, 4, 4});
  size_t wrong = 0;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 517; ++x)
      wrong += fb.colorAt(x, y) != glm::vec4(0.25f, 0.5f, 0.75f, 1.0f) || fb.depthAt(x, y) != 0.5 ||
               fb.stencilAt(x, y) != 3 || fb.accumAt(x, y) != glm::vec4(-0.5f, 0.0f, 0.5f, 1.0f);
  CHECK(wrong == 0);

  // A scissored clear: rows 10..209, columns 7..506 (100 000 pixels, 3 parts of rows cut apart).
  s.scissorTest = true;
  s.scissor = {7, 10, 500, 200};
  clearStencil(fb, s, 9, parallel.fn());
  CHECK(parallel.counts.back() == 3);
  size_t inside = 0, outside = 0;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 517; ++x) {
      const bool in = x >= 7 && x < 507 && y >= 10 && y < 210;
      if (fb.stencilAt(x, y) == (in ? 9 : 3)) (in ? inside : outside) += 1;
    }
  CHECK(inside == 100000u);
  CHECK(outside == 517u * 300u - 100000u);
}

TEST_CASE("a clear of a small buffer is one part, on the calling thread", "[raster][clear][threads]") {
  Framebuffer fb(160, 128);
  RecordingParallel parallel;
  clearDepth(fb, fullViewportState(fb), 1.0, parallel.fn());
  CHECK(parallel.counts.empty());
  CHECK(fb.depthAt(159, 127) == 1.0);
}
