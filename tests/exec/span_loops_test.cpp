// The span kernels (stencil counting, depth only, constant colour, general) against the renderer
// run one fragment at a time (Renderer::oneFragmentAtATime), which sends every fragment through
// the one-fragment function of the pixel history: the same triangles in
// random render states must leave the same bytes in every buffer and the same counters.
#include <algorithm>
#include <cstring>

#include <catch2/catch.hpp>

#include "exec/renderer.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

struct Drawn {
  Framebuffer fb;
  RasterStats stats;
};

StencilOp randomOp(TestRandom& r, bool wrapOnly) {
  static const StencilOp wrap[] = {StencilOp::Keep, StencilOp::IncrWrap, StencilOp::DecrWrap};
  if (wrapOnly) return wrap[r.below(3)];
  return StencilOp(r.below(8));
}

// A state of one of the shapes the span loops distinguish (0 volume pass, 1 depth map, 3 colour
// pass that only reads the stencil, 4 ambient pass: no stencil, no blending, every channel), or
// anything at all (2).
RenderState randomState(TestRandom& r, const Framebuffer& fb, int shape) {
  RenderState s = fullViewportState(fb);
  s.depthTest = r.below(5) != 0;
  s.depthFunc = CompareFunc(r.below(8));
  s.depthWrite = r.below(2) == 0;
  s.depthClamp = r.below(4) == 0;
  s.viewport.nearVal = r.below(3) == 0 ? 0.25 : 0.0;
  s.viewport.farVal = r.below(3) == 0 ? 0.75 : 1.0;
  s.cull = CullMode(r.below(3));
  s.polygonOffset = {r.below(3) == 0, r.uniform(-2.0, 2.0), double(r.below(5)) - 2.0};
  s.stencilTest = r.below(3) != 0;
  for (StencilFaceState& f : s.stencil) {
    f.func = CompareFunc(r.below(8));
    f.ref = r.below(300) - 20;
    f.mask = r.below(2) ? 0xFF : uint8_t(r.below(256));
    f.writeMask = r.below(2) ? 0xFF : uint8_t(r.below(256));
    f.sfail = randomOp(r, false);
    f.dpfail = randomOp(r, false);
    f.dppass = randomOp(r, false);
  }
  s.blend = {r.below(2) == 0, BlendFactor(r.below(10)), BlendFactor(r.below(10))};
  for (bool& m : s.colorMask) m = r.below(4) != 0;
  if (shape == 0) {  // a shadow-volume pass
    s.stencilTest = true;
    s.depthWrite = false;
    s.colorMask = {false, false, false, false};
    for (StencilFaceState& f : s.stencil) {
      f.func = CompareFunc::Always;
      f.writeMask = 0xFF;
      f.dpfail = randomOp(r, true);
      f.dppass = randomOp(r, true);
    }
  } else if (shape == 1) {  // a depth-map pass
    s.stencilTest = false;
    s.colorMask = {false, false, false, false};
  } else if (shape == 4) {  // an ambient pass: one colour where the depth test passes
    s.stencilTest = false;
    s.blend.enabled = false;
    s.colorMask = {true, true, true, true};
  } else if (shape == 3) {  // an ambient, lit or darken pass: the stencil only filters
    static const CompareFunc stencilFuncs[] = {CompareFunc::Equal, CompareFunc::NotEqual, CompareFunc::Always};
    static const CompareFunc depthFuncs[] = {CompareFunc::Less, CompareFunc::LEqual};
    s.depthFunc = depthFuncs[r.below(2)];
    for (StencilFaceState& f : s.stencil) {
      f.func = stencilFuncs[r.below(3)];
      f.ref = r.below(3);
      f.sfail = f.dpfail = f.dppass = StencilOp::Keep;
      if (r.below(4) == 0) {  // ops that write, behind a zero write mask
        f.dppass = StencilOp::Invert;
        f.writeMask = 0;
      }
    }
  }
  return s;
}

std::vector<ClipVertex> randomTriangles(TestRandom& r, const Viewport& vp, int count) {
  std::vector<ClipVertex> out;
  for (int i = 0; i < count; ++i) {
    // Centres up to 10 pixels outside the viewport, sizes up to its larger side and down to one
    // pixel: rows from one pixel to the whole width, at both ends of the rows.
    const double right = vp.width + 10.0, top = vp.height + 10.0, most = std::max(vp.width, vp.height);
    const double cx = r.uniform(-10.0, right), cy = r.uniform(-10.0, top), size = r.uniform(1.0, most);
    for (int k = 0; k < 3; ++k) {
      ClipVertex v = windowVertex(vp, cx + r.uniform(-size, size), cy + r.uniform(-size, size), r.uniform(-0.2, 1.2));
      const double w = r.uniform(0.5, 3.0);  // perspective: varyings and depth vary non-linearly
      v.position *= w;
      for (int c = 0; c < 4; ++c) v.varyings[size_t(c)] = r.uniform(-0.2, 1.2);
      out.push_back(v);
    }
  }
  return out;
}

// A colour from the pixel and one varying, through the default batch form
// (FragmentShader::shadeBatch): fragments shaded together across the rows of a triangle must each
// keep their own pixel.
class PixelShader final : public FragmentShader {
 public:
  int varyingCount() const override { return 1; }
  glm::dvec4 shade(const FragmentInput& in) const override {
    return {double(in.x % 7) / 7.0, double(in.y % 5) / 5.0, in.varyings[0], 1.0};
  }
};

Drawn drawWith(bool reference, int width, int height, DepthFormat format, const std::vector<RenderState>& states,
               const std::vector<std::vector<ClipVertex>>& batches, int threads) {
  Renderer::oneFragmentAtATime(reference);
  Drawn d{Framebuffer(width, height, format), {}};
  Renderer renderer(d.fb, threads);
  Renderer::oneFragmentAtATime(false);
  const ColorVaryingShader varying;
  const ConstantColorShader constant({0.3, 0.6, 0.9, 0.5});
  const PixelShader pixel;
  const FragmentShader* const shaders[] = {nullptr, &varying, &constant, &pixel};
  for (size_t i = 0; i < states.size(); ++i) {
    const FragmentShader* shader = shaders[i % 4];
    draw(renderer, states[i], batches[i], shader);
  }
  d.stats = renderer.stats();
  return d;
}

bool sameColor(const Framebuffer& a, const Framebuffer& b) {
  return a.color().size() == b.color().size() &&
         (a.color().empty() || std::memcmp(a.color().data(), b.color().data(), a.color().size() * sizeof(glm::vec4)) == 0);
}

// Every buffer's bytes and every counter the same.
void checkSame(const Drawn& reference, const Drawn& spans) {
  CHECK(reference.fb.stencil() == spans.fb.stencil());
  CHECK(reference.fb.depthCodes() == spans.fb.depthCodes());
  CHECK(sameColor(reference.fb, spans.fb));
  CHECK(reference.stats.fragments == spans.stats.fragments);
  CHECK(reference.stats.stencilFailed == spans.stats.stencilFailed);
  CHECK(reference.stats.depthFailed == spans.stats.depthFailed);
  CHECK(reference.stats.stencilWrites == spans.stats.stencilWrites);
  CHECK(reference.stats.colorWrites == spans.stats.colorWrites);
}

}  // namespace

TEST_CASE("span loops leave the same bytes as the one-fragment path, in random states", "[raster][spans]") {
  const int shape = GENERATE(0, 1, 2, 3, 4);
  const DepthFormat format = GENERATE(DepthFormat::Float32, DepthFormat::Unorm24);
  // 64 wide: rows' last pixels in one step of eight; 8 and 9 wide: that step at the row's end
  // reaching back over pixels already done; 5 wide: rows shorter than any step, pixel by pixel.
  const auto [width, height] = GENERATE(std::pair{64, 64}, std::pair{9, 40}, std::pair{8, 24}, std::pair{5, 40});
  for (uint64_t seed = 1; seed <= 12; ++seed) {
    INFO("shape " << shape << ", " << width << "x" << height << ", seed " << seed);
    TestRandom r(seed * 7919 + uint64_t(shape));
    Framebuffer probe(width, height, format);
    std::vector<RenderState> states;
    std::vector<std::vector<ClipVertex>> batches;
    for (int draw = 0; draw < 12; ++draw) {
      states.push_back(randomState(r, probe, draw == 0 ? 2 : shape));
      batches.push_back(randomTriangles(r, states.back().viewport, 6));
    }
    const Drawn reference = drawWith(true, width, height, format, states, batches, 1);
    const Drawn spans = drawWith(false, width, height, format, states, batches, 1);
    REQUIRE(reference.stats.fragments > 0);
    checkSame(reference, spans);
  }
}

namespace {

// A 256x64 screen-filling rectangle drawn over a stencil holding `shadow` in columns [40, 180) of
// rows [10, 50) and `lit` everywhere else: its rows are four chunks of 64, the first and third
// cut by the shadow's edges, the second all in it. Back-facing when `back` (the corners in the
// other order).
Drawn drawOverShadow(bool reference, const StencilFaceState& face, bool back, uint8_t lit, uint8_t shadow) {
  Renderer::oneFragmentAtATime(reference);
  Drawn d{Framebuffer(256, 64), {}};
  Renderer renderer(d.fb, 1);
  Renderer::oneFragmentAtATime(false);
  d.fb.ensureStencil();
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 256; ++x) d.fb.stencil()[d.fb.index(x, y)] = x >= 40 && x < 180 && y >= 10 && y < 50 ? shadow : lit;
  RenderState s = fullViewportState(d.fb);
  s.stencilTest = true;
  s.stencil = {face, face};
  s.depthTest = true;
  s.depthFunc = CompareFunc::Less;
  std::vector<ClipVertex> rect = windowRect(s.viewport, 0.0, 0.0, 256.0, 64.0, 0.5);
  if (back)
    for (size_t i = 0; i < rect.size(); i += 3) std::swap(rect[i + 1], rect[i + 2]);
  const ConstantColorShader white({1.0, 1.0, 1.0, 1.0});
  draw(renderer, s, rect, &white);
  d.stats = renderer.stats();
  return d;
}

}  // namespace

// A lit pass's chunks whose every fragment fails a stencil test that writes nothing are counted
// and skipped before their depths are made (FragmentProcessor::runSpan); one whose fail op writes
// is not. Checked by hand (the shadow is 140 x 40 = 5600 pixels of 16384) and against the
// one-fragment path.
TEST_CASE("chunks the stencil test discards whole are counted, not tested further", "[raster][spans]") {
  constexpr uint64_t kPixels = 256 * 64, kShadow = 140 * 40;
  SECTION("equal to 0, keep: the shadow is not lit, its depth not written") {
    StencilFaceState face;
    face.func = CompareFunc::Equal;
    face.ref = 0;
    const Drawn spans = drawOverShadow(false, face, false, 0, 1);
    CHECK(spans.stats.fragments == kPixels);
    CHECK(spans.stats.stencilFailed == kShadow);
    CHECK(spans.stats.colorWrites == kPixels - kShadow);
    const Framebuffer& fb = spans.fb;
    CHECK(fb.color()[fb.index(100, 30)] == glm::vec4(0.0f));  // in the shadow
    CHECK(fb.color()[fb.index(39, 30)] == glm::vec4(1.0f));   // just left of it
    CHECK(fb.color()[fb.index(180, 30)] == glm::vec4(1.0f));  // just right of it
    CHECK(fb.depthCodes()[fb.index(100, 30)] == fb.depthCodec().encode(1.0));
    CHECK(fb.depthCodes()[fb.index(10, 30)] == fb.depthCodec().encode(0.5));
    checkSame(drawOverShadow(true, face, false, 0, 1), spans);
  }
  SECTION("greater through a mask, on back faces: 2 > (0x13 & 0x0F) fails, 2 > (0x01 & 0x0F) passes") {
    StencilFaceState face;
    face.func = CompareFunc::Greater;
    face.ref = 2;
    face.mask = 0x0F;
    const Drawn spans = drawOverShadow(false, face, true, 0x01, 0x13);
    CHECK(spans.stats.stencilFailed == kShadow);
    CHECK(spans.stats.colorWrites == kPixels - kShadow);
    checkSame(drawOverShadow(true, face, true, 0x01, 0x13), spans);
  }
  SECTION("a fail op that writes: every failing fragment still replaces its stencil") {
    StencilFaceState face;
    face.func = CompareFunc::Equal;
    face.ref = 0;
    face.sfail = StencilOp::Replace;
    const Drawn spans = drawOverShadow(false, face, false, 0, 1);
    CHECK(spans.stats.stencilFailed == kShadow);
    CHECK(std::all_of(spans.fb.stencil().begin(), spans.fb.stencil().end(), [](uint8_t v) { return v == 0; }));
    checkSame(drawOverShadow(true, face, false, 0, 1), spans);
  }
}
