// The per-fragment operations in order (gl/per_fragment.h) on one fragment, with the pixel
// history's event: each expected byte worked out from [GL 2.1, §4.1].
#include <catch2/catch.hpp>

#include <vector>

#include "gl/per_fragment.h"
#include "gl/stage_fixtures.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

class Recorder final : public FragmentObserver {
 public:
  void onFragment(const FragmentEvent& e) override { events.push_back(e); }
  std::vector<FragmentEvent> events;
};

// A 2x2 framebuffer with stencil `stored` and depth `storedDepth` everywhere, and a triangle at
// depth 0.5 over all of it.
struct OneFragment {
  Framebuffer fb{2, 2};
  RenderState state;
  TriangleSetup t;
  RasterStats stats;
  Recorder recorder;
  PixelWatch watch;
  OneFragment(uint8_t stored, double storedDepth) {
    fb.ensureStencil();
    fb.ensureDepth();
    for (uint8_t& s : fb.stencil()) s = stored;
    for (uint32_t& d : fb.depthCodes()) d = fb.depthCodec().encode(storedDepth);
    state.viewport = {0, 0, 2, 2, 0.0, 1.0};
    t = setupOf(windowAt(-4, -4, 0.5), windowAt(8, -4, 0.5), windowAt(-4, 8, 0.5), state);
    watch.x = 1;
    watch.y = 0;
    watch.observer = &recorder;
    watch.drawIndex = 7;
    watch.drawTag = 42;
    watch.hasDepth = watch.hasStencil = true;  // the buffers the draw found
  }
  void run() {
    CoveredPixel p{1, 0, {}};
    processFragment(fb, state, nullptr, bufferUse(fb, state, nullptr), t, p, stats, &watch);
  }
};

}  // namespace

TEST_CASE("z-fail: DECR_WRAP turns a stencil byte of 0 into 255 when the depth test fails", "[gl][per_fragment]") {
  // Stored depth 0.25, fragment 0.5, LESS: the depth test fails, the stencil test (ALWAYS)
  // passed, so dpfail runs: DECR_WRAP of 0 wraps to 255 ([GL 2.1, §4.1.5]).
  OneFragment f(0, 0.25);
  f.state.stencilTest = true;
  f.state.depthTest = true;
  f.state.stencil[FrontFacing].dpfail = StencilOp::DecrWrap;
  f.run();
  CHECK(int(f.fb.stencilAt(1, 0)) == 255);
  CHECK(int(f.fb.stencilAt(0, 0)) == 0);  // the other pixels untouched
  CHECK(f.fb.depthAt(1, 0) == 0.25);     // a failing fragment writes no depth
  CHECK(f.stats.fragments == 1);
  CHECK(f.stats.depthFailed == 1);
  CHECK(f.stats.stencilWrites == 1);
  CHECK(f.stats.stencilFailed == 0);
  REQUIRE(f.recorder.events.size() == 1);
  const FragmentEvent& e = f.recorder.events[0];
  CHECK(e.drawIndex == 7);
  CHECK(e.drawTag == 42);
  CHECK(e.stencilPassed);
  CHECK_FALSE(e.depthPassed);
  CHECK(int(e.stencilBefore) == 0);
  CHECK(int(e.stencilAfter) == 255);
  CHECK(e.storedDepth == 0.25);
  CHECK(e.depth == 0.5);
}

TEST_CASE("z-pass: a passing fragment takes dppass and writes its depth", "[gl][per_fragment]") {
  OneFragment f(255, 1.0);
  f.state.stencilTest = true;
  f.state.depthTest = true;
  f.state.stencil[FrontFacing].dppass = StencilOp::IncrWrap;  // 255 -> 0
  f.run();
  CHECK(int(f.fb.stencilAt(1, 0)) == 0);
  CHECK(f.fb.depthAt(1, 0) == 0.5);
  CHECK(f.stats.depthFailed == 0);
  CHECK(f.stats.stencilWrites == 1);
}

TEST_CASE("a fragment failing the stencil test takes sfail and is not depth tested", "[gl][per_fragment]") {
  // Stored 3, EQUAL 0 fails; sfail INVERT makes 0xFC through write mask 0xFF; the depth (which
  // would pass) is neither tested nor written.
  OneFragment f(3, 1.0);
  f.state.stencilTest = true;
  f.state.depthTest = true;
  f.state.stencil[FrontFacing] = {CompareFunc::Equal, 0, 0xFF, 0x0F, StencilOp::Invert, StencilOp::Keep, StencilOp::Keep};
  f.run();
  // INVERT of 0x03 is 0xFC; through write mask 0x0F: (0x03 & 0xF0) | (0xFC & 0x0F) = 0x0C.
  CHECK(int(f.fb.stencilAt(1, 0)) == 0x0C);
  CHECK(f.fb.depthAt(1, 0) == 1.0);
  CHECK(f.stats.stencilFailed == 1);
  CHECK(f.stats.depthFailed == 0);
  REQUIRE(f.recorder.events.size() == 1);
  CHECK_FALSE(f.recorder.events[0].stencilPassed);
}

TEST_CASE("colour: the shader's colour blended with the stored one and written through the mask", "[gl][per_fragment]") {
  Framebuffer fb(1, 1);
  fb.ensureColor();
  fb.color()[0] = glm::vec4(0.5f, 0.5f, 0.5f, 0.5f);
  RenderState state;
  state.viewport = {0, 0, 1, 1, 0.0, 1.0};
  state.blend = {true, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha};
  state.colorMask = {true, true, false, true};
  const ConstantColorShader shader(glm::dvec4(1.0, 0.0, 2.0, 0.25));
  const TriangleSetup t = setupOf(windowAt(-4, -4), windowAt(8, -4), windowAt(-4, 8), state);
  RasterStats stats;
  processFragment(fb, state, &shader, bufferUse(fb, state, &shader), t, CoveredPixel{0, 0, {}}, stats, nullptr);
  // src clamped to (1, 0, 1, 0.25); out = src * 0.25 + dst * 0.75: r 0.625, g 0.375, a 0.4375;
  // blue is masked and keeps 0.5.
  CHECK(fb.color()[0] == glm::vec4(0.625f, 0.375f, 0.5f, 0.4375f));
  CHECK(stats.colorWrites == 1);
}
