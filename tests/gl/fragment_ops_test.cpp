// The per-fragment operations of [GL 2.1, §4.1], each checked through a real draw: a rectangle over
// a row of pixels whose stored stencil / depth / colour values differ, so one draw shows the
// operation on every interesting input at once. Expected rows are written out by hand.
#include <array>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "gl/fragment_ops.h"
#include "exec/renderer.h"
#include "support/raster_harness.h"

using namespace shadowref;
using namespace shadowref::testing;

namespace {

// A 1-pixel-high strip whose stencil holds `stored`, covered completely by one rectangle at depth
// `z`. Returns the stencil afterwards.
std::vector<uint8_t> stencilAfterDraw(const std::vector<uint8_t>& stored, const RenderState& stateIn,
                                      double z = 0.5, const std::vector<double>& storedDepth = {}) {
  Framebuffer fb(int(stored.size()), 1);
  RenderState state = stateIn;
  state.viewport = fullViewportState(fb).viewport;
  fb.ensureStencil();
  std::copy(stored.begin(), stored.end(), fb.stencil().begin());
  if (!storedDepth.empty()) {
    fb.ensureDepth();
    for (size_t i = 0; i < storedDepth.size(); ++i) fb.depthCodes()[i] = fb.depthCodec().encode(storedDepth[i]);
  }
  Renderer r(fb);
  draw(r, state, windowRect(state.viewport, 0, 0, fb.width(), 1, z));
  return {fb.stencil().begin(), fb.stencil().end()};
}

// Which pixels of the strip a white rectangle reached ('#') and which it did not ('.').
std::string passPattern(const Framebuffer& fb) {
  return picture(fb.width(), fb.height(), [&](int x, int y) { return fb.colorAt(x, y).r == 1.0f ? '#' : '.'; });
}

std::string stencilFuncPattern(CompareFunc func, int ref, uint8_t mask, const std::vector<uint8_t>& stored) {
  Framebuffer fb(int(stored.size()), 1);
  RenderState state = fullViewportState(fb);
  fb.ensureColor();
  fb.ensureStencil();
  std::copy(stored.begin(), stored.end(), fb.stencil().begin());
  state.stencilTest = true;
  state.stencil[FrontFacing].func = func;
  state.stencil[FrontFacing].ref = ref;
  state.stencil[FrontFacing].mask = mask;
  Renderer r(fb);
  const ConstantColorShader white({1.0, 1.0, 1.0, 1.0});
  draw(r, state, windowRect(state.viewport, 0, 0, fb.width(), 1), &white);
  CHECK(std::vector<uint8_t>(fb.stencil().begin(), fb.stencil().end()) == stored);  // all ops KEEP
  return passPattern(fb);
}

std::string depthFuncPattern(CompareFunc func, DepthFormat format, double z, const std::vector<double>& stored,
                             std::vector<double>* depthAfter = nullptr, bool depthWrite = true) {
  Framebuffer fb(int(stored.size()), 1, format);
  RenderState state = fullViewportState(fb);
  fb.ensureColor();
  fb.ensureDepth();
  for (size_t i = 0; i < stored.size(); ++i) fb.depthCodes()[i] = fb.depthCodec().encode(stored[i]);
  state.depthTest = true;
  state.depthFunc = func;
  state.depthWrite = depthWrite;
  Renderer r(fb);
  const ConstantColorShader white({1.0, 1.0, 1.0, 1.0});
  draw(r, state, windowRect(state.viewport, 0, 0, fb.width(), 1, z), &white);
  if (depthAfter) {
    depthAfter->clear();
    for (int x = 0; x < fb.width(); ++x) depthAfter->push_back(fb.depthAt(x, 0));
  }
  return passPattern(fb);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Stencil test: (ref & mask) FUNC (stored & mask), [GL 2.1, §4.1.5].

TEST_CASE("stencil func compares ref against the stored value, full mask", "[raster][stencil]") {
  // stored 0x20 0x35 0x3A 0x40, ref 0x35, mask 0xFF
  const std::vector<uint8_t> stored{0x20, 0x35, 0x3A, 0x40};
  CHECK(stencilFuncPattern(CompareFunc::Never, 0x35, 0xFF, stored) == "....");
  CHECK(stencilFuncPattern(CompareFunc::Less, 0x35, 0xFF, stored) == "..##");      // ref < stored
  CHECK(stencilFuncPattern(CompareFunc::Equal, 0x35, 0xFF, stored) == ".#..");
  CHECK(stencilFuncPattern(CompareFunc::LEqual, 0x35, 0xFF, stored) == ".###");
  CHECK(stencilFuncPattern(CompareFunc::Greater, 0x35, 0xFF, stored) == "#...");   // ref > stored
  CHECK(stencilFuncPattern(CompareFunc::NotEqual, 0x35, 0xFF, stored) == "#.##");
  CHECK(stencilFuncPattern(CompareFunc::GEqual, 0x35, 0xFF, stored) == "##..");
  CHECK(stencilFuncPattern(CompareFunc::Always, 0x35, 0xFF, stored) == "####");
}

TEST_CASE("stencil func masks both ref and stored value before comparing", "[raster][stencil]") {
  // mask 0xF0: stored becomes 0x20 0x30 0x30 0x40, ref 0x35 becomes 0x30
  const std::vector<uint8_t> stored{0x20, 0x35, 0x3A, 0x40};
  CHECK(stencilFuncPattern(CompareFunc::Never, 0x35, 0xF0, stored) == "....");
  CHECK(stencilFuncPattern(CompareFunc::Less, 0x35, 0xF0, stored) == "...#");
  CHECK(stencilFuncPattern(CompareFunc::Equal, 0x35, 0xF0, stored) == ".##.");
  CHECK(stencilFuncPattern(CompareFunc::LEqual, 0x35, 0xF0, stored) == ".###");
  CHECK(stencilFuncPattern(CompareFunc::Greater, 0x35, 0xF0, stored) == "#...");
  CHECK(stencilFuncPattern(CompareFunc::NotEqual, 0x35, 0xF0, stored) == "#..#");
  CHECK(stencilFuncPattern(CompareFunc::GEqual, 0x35, 0xF0, stored) == "###.");
  CHECK(stencilFuncPattern(CompareFunc::Always, 0x35, 0xF0, stored) == "####");
  // mask 0x00: everything compares as 0 == 0
  CHECK(stencilFuncPattern(CompareFunc::Equal, 0x35, 0x00, stored) == "####");
  CHECK(stencilFuncPattern(CompareFunc::Less, 0x35, 0x00, stored) == "....");
}

TEST_CASE("stencil ref is clamped to [0, 255] before masking", "[raster][stencil]") {
  const std::vector<uint8_t> stored{0x00, 0x01, 0xFE, 0xFF};
  CHECK(stencilFuncPattern(CompareFunc::Equal, 300, 0xFF, stored) == "...#");   // 300 -> 255
  CHECK(stencilFuncPattern(CompareFunc::Equal, -7, 0xFF, stored) == "#...");    // -7 -> 0
  CHECK(stencilFuncPattern(CompareFunc::Greater, 256, 0xFF, stored) == "###.");
}

// ---------------------------------------------------------------------------------------------
// Stencil ops on each path. The strip holds 0, 1, 2, 0x5A, 0x80, 0xFD, 0xFE, 0xFF; ref 0x33.

namespace {

const std::vector<uint8_t> kOpInput{0x00, 0x01, 0x02, 0x5A, 0x80, 0xFD, 0xFE, 0xFF};
constexpr int kOpRef = 0x33;

struct OpCase {
  StencilOp op;
  std::vector<uint8_t> expected;
};

const std::vector<OpCase>& opCases() {
  static const std::vector<OpCase> cases{
      {StencilOp::Keep, {0x00, 0x01, 0x02, 0x5A, 0x80, 0xFD, 0xFE, 0xFF}},
      {StencilOp::Zero, {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}},
      {StencilOp::Replace, {0x33, 0x33, 0x33, 0x33, 0x33, 0x33, 0x33, 0x33}},
      {StencilOp::Incr, {0x01, 0x02, 0x03, 0x5B, 0x81, 0xFE, 0xFF, 0xFF}},      // saturates at 255
      {StencilOp::Decr, {0x00, 0x00, 0x01, 0x59, 0x7F, 0xFC, 0xFD, 0xFE}},      // saturates at 0
      {StencilOp::Invert, {0xFF, 0xFE, 0xFD, 0xA5, 0x7F, 0x02, 0x01, 0x00}},
      {StencilOp::IncrWrap, {0x01, 0x02, 0x03, 0x5B, 0x81, 0xFE, 0xFF, 0x00}},  // 255 -> 0
      {StencilOp::DecrWrap, {0xFF, 0x00, 0x01, 0x59, 0x7F, 0xFC, 0xFD, 0xFE}},  // 0 -> 255
  };
  return cases;
}

// The ops of the two paths that must not fire: something visibly different from the op under test.
StencilOp otherOp(StencilOp op) { return op == StencilOp::Invert ? StencilOp::Zero : StencilOp::Invert; }

}  // namespace

TEST_CASE("every stencil op applies on the sfail path (stencil test failed)", "[raster][stencil]") {
  for (const OpCase& c : opCases()) {
    INFO("op " << name(c.op));
    RenderState s;
    s.stencilTest = true;
    s.stencil[FrontFacing] = {CompareFunc::Never, kOpRef, 0xFF, 0xFF, c.op, otherOp(c.op), otherOp(c.op)};
    // The depth test would pass; it must not even be consulted after a stencil failure.
    s.depthTest = true;
    s.depthFunc = CompareFunc::Always;
    CHECK(stencilAfterDraw(kOpInput, s) == c.expected);
  }
}

TEST_CASE("every stencil op applies on the dpfail path (stencil passed, depth failed)", "[raster][stencil]") {
  for (const OpCase& c : opCases()) {
    INFO("op " << name(c.op));
    RenderState s;
    s.stencilTest = true;
    s.stencil[FrontFacing] = {CompareFunc::Always, kOpRef, 0xFF, 0xFF, otherOp(c.op), c.op, otherOp(c.op)};
    s.depthTest = true;
    s.depthFunc = CompareFunc::Less;  // fragment 0.5 against stored 0.25 fails
    CHECK(stencilAfterDraw(kOpInput, s, 0.5, std::vector<double>(8, 0.25)) == c.expected);
  }
}

TEST_CASE("every stencil op applies on the dppass path (both tests passed)", "[raster][stencil]") {
  for (const OpCase& c : opCases()) {
    INFO("op " << name(c.op));
    RenderState s;
    s.stencilTest = true;
    s.stencil[FrontFacing] = {CompareFunc::Always, kOpRef, 0xFF, 0xFF, otherOp(c.op), otherOp(c.op), c.op};
    s.depthTest = true;
    s.depthFunc = CompareFunc::Less;  // fragment 0.5 against stored 0.75 passes
    CHECK(stencilAfterDraw(kOpInput, s, 0.5, std::vector<double>(8, 0.75)) == c.expected);
  }
}

TEST_CASE("INCR saturates at 255 and INCR_WRAP wraps to 0 over 300 draws", "[raster][stencil]") {
  RenderState s;
  s.stencilTest = true;
  Framebuffer fb(2, 1);
  s.viewport = fullViewportState(fb).viewport;
  s.stencil[FrontFacing].dppass = StencilOp::Incr;
  RenderState wrap = s;
  wrap.stencil[FrontFacing].dppass = StencilOp::IncrWrap;
  Renderer r(fb);
  for (int i = 0; i < 300; ++i) {
    draw(r, s, windowRect(s.viewport, 0, 0, 1, 1));
    draw(r, wrap, windowRect(s.viewport, 1, 0, 2, 1));
  }
  CHECK(fb.stencilAt(0, 0) == 255);
  CHECK(fb.stencilAt(1, 0) == 300 - 256);
}

TEST_CASE("DECR saturates at 0 and DECR_WRAP wraps to 255", "[raster][stencil]") {
  RenderState s;
  s.stencilTest = true;
  s.stencil[FrontFacing].dppass = StencilOp::Decr;
  CHECK(stencilAfterDraw({0, 0}, s) == std::vector<uint8_t>{0, 0});
  s.stencil[FrontFacing].dppass = StencilOp::DecrWrap;
  const std::vector<uint8_t> once = stencilAfterDraw({0, 1}, s);
  CHECK(once == std::vector<uint8_t>{255, 0});
}

TEST_CASE("stencil write mask lets only its bits change, on every path", "[raster][stencil]") {
  RenderState s;
  s.stencilTest = true;
  // REPLACE 0x55 into 0xAA through mask 0x0F: (0xAA & 0xF0) | (0x55 & 0x0F) = 0xA5
  s.stencil[FrontFacing] = {CompareFunc::Always, 0x55, 0xFF, 0x0F, StencilOp::Keep, StencilOp::Keep,
                            StencilOp::Replace};
  CHECK(stencilAfterDraw({0xAA}, s) == std::vector<uint8_t>{0xA5});
  // INCR through mask 0x01: 0x01 -> 0x02 keeps bit 1 of the old value (0) -> 0x00; 0xFF stays
  s.stencil[FrontFacing] = {CompareFunc::Always, 0, 0xFF, 0x01, StencilOp::Keep, StencilOp::Keep,
                            StencilOp::Incr};
  CHECK(stencilAfterDraw({0x01, 0xFF, 0x10}, s) == std::vector<uint8_t>{0x00, 0xFF, 0x11});
  // sfail ZERO through mask 0xF0 clears only the high nibble
  s.stencil[FrontFacing] = {CompareFunc::Never, 0, 0xFF, 0xF0, StencilOp::Zero, StencilOp::Keep,
                            StencilOp::Keep};
  CHECK(stencilAfterDraw({0xAB, 0x0C}, s) == std::vector<uint8_t>{0x0B, 0x0C});
  // write mask 0: nothing changes at all
  s.stencil[FrontFacing] = {CompareFunc::Always, 0, 0xFF, 0x00, StencilOp::Invert, StencilOp::Invert,
                            StencilOp::Invert};
  CHECK(stencilAfterDraw({0xAB, 0x0C}, s) == std::vector<uint8_t>{0xAB, 0x0C});
}

TEST_CASE("stencilOpMayWrite is true exactly for the op and mask that change some stored byte",
          "[raster][stencil]") {
  // Against the definition, over every stored byte and write mask and references inside and outside
  // [0, 255]: an op "may write" when some stored value comes out of the op and the mask changed.
  const StencilOp ops[] = {StencilOp::Keep, StencilOp::Zero,     StencilOp::Replace,  StencilOp::Incr,
                           StencilOp::Decr, StencilOp::Invert, StencilOp::IncrWrap, StencilOp::DecrWrap};
  const int refs[] = {-5, 0, 1, 128, 255, 300};
  int mayWrite = 0;
  for (const StencilOp op : ops) {
    for (int mask = 0; mask < 256; ++mask) {
      bool changes = false;
      for (const int ref : refs)
        for (int stored = 0; stored < 256 && !changes; ++stored)
          changes = writeStencil(uint8_t(stored), applyStencilOp(op, uint8_t(stored), ref), uint8_t(mask)) != stored;
      INFO("op " << name(op) << ", write mask " << mask);
      CHECK(stencilOpMayWrite(op, uint8_t(mask)) == changes);
      mayWrite += changes;
    }
  }
  CHECK(mayWrite == 7 * 255);  // every op but KEEP, through every mask but 0
}

TEST_CASE("stencilFaceMayWrite asks all three ops through the face's write mask", "[raster][stencil]") {
  StencilFaceState f;  // KEEP, KEEP, KEEP
  CHECK_FALSE(stencilFaceMayWrite(f));
  f.dpfail = StencilOp::IncrWrap;  // z-fail's back faces
  CHECK(stencilFaceMayWrite(f));
  f.writeMask = 0;
  CHECK_FALSE(stencilFaceMayWrite(f));
  f = StencilFaceState{};
  f.sfail = StencilOp::Zero;
  CHECK(stencilFaceMayWrite(f));
  f = StencilFaceState{};
  f.dppass = StencilOp::Replace;
  f.writeMask = 0x80;
  CHECK(stencilFaceMayWrite(f));
}

// ---------------------------------------------------------------------------------------------
// Depth test ([GL 2.1, §4.1.6]): the fragment's code FUNC the stored code.

TEST_CASE("every depth func compares the fragment depth against the stored depth", "[raster][depth]") {
  const std::vector<double> stored{0.25, 0.5, 0.75, 1.0};
  for (DepthFormat format : {DepthFormat::Float32, DepthFormat::Unorm24}) {
    INFO((format == DepthFormat::Float32 ? "float32" : "unorm24"));
    CHECK(depthFuncPattern(CompareFunc::Never, format, 0.5, stored) == "....");
    CHECK(depthFuncPattern(CompareFunc::Less, format, 0.5, stored) == "..##");
    CHECK(depthFuncPattern(CompareFunc::Equal, format, 0.5, stored) == ".#..");
    CHECK(depthFuncPattern(CompareFunc::LEqual, format, 0.5, stored) == ".###");
    CHECK(depthFuncPattern(CompareFunc::Greater, format, 0.5, stored) == "#...");
    CHECK(depthFuncPattern(CompareFunc::NotEqual, format, 0.5, stored) == "#.##");
    CHECK(depthFuncPattern(CompareFunc::GEqual, format, 0.5, stored) == "##..");
    CHECK(depthFuncPattern(CompareFunc::Always, format, 0.5, stored) == "####");
  }
}

TEST_CASE("a passing fragment writes its depth, a failing one leaves the stored depth", "[raster][depth]") {
  std::vector<double> after;
  CHECK(depthFuncPattern(CompareFunc::Less, DepthFormat::Float32, 0.5, {0.25, 0.5, 0.75, 1.0}, &after) == "..##");
  CHECK(after == std::vector<double>{0.25, 0.5, 0.5, 0.5});
}

TEST_CASE("depth mask off: the test still decides, but no depth is written", "[raster][depth]") {
  std::vector<double> after;
  CHECK(depthFuncPattern(CompareFunc::Less, DepthFormat::Float32, 0.5, {0.25, 0.5, 0.75, 1.0}, &after,
                         /*depthWrite=*/false) == "..##");
  CHECK(after == std::vector<double>{0.25, 0.5, 0.75, 1.0});
}

TEST_CASE("depth is compared in the buffer's format: one float ulp is below unorm24 resolution",
          "[raster][depth]") {
  // 0.25 and 0.25 + 2^-25 are neighbouring floats, but both round to unorm24 code 4194304
  // (0.25 * (2^24 - 1) = 4194303.75 and + 0.49999997).
  const double z = 0.25, stored = 0.25 + 0x1.0p-25;
  CHECK(depthFuncPattern(CompareFunc::Less, DepthFormat::Float32, z, {stored}) == "#");
  CHECK(depthFuncPattern(CompareFunc::Less, DepthFormat::Unorm24, z, {stored}) == ".");
  CHECK(depthFuncPattern(CompareFunc::Equal, DepthFormat::Unorm24, z, {stored}) == "#");
}

// ---------------------------------------------------------------------------------------------
// Blending ([GL 2.1, §4.1.8]), equation FUNC_ADD, result clamped to [0, 1] by the colour buffer.

namespace {

glm::vec4 blendOver(const glm::vec4& dst, const glm::dvec4& src, BlendFactor sf, BlendFactor df,
                    std::array<bool, 4> mask = {true, true, true, true}) {
  Framebuffer fb(1, 1);
  fb.ensureColor();
  fb.color()[0] = dst;
  RenderState s = fullViewportState(fb);
  s.blend = {true, sf, df};
  s.colorMask = mask;
  Renderer r(fb);
  const ConstantColorShader shader(src);
  draw(r, s, windowRect(s.viewport, 0, 0, 1, 1), &shader);
  return fb.colorAt(0, 0);
}

}  // namespace

TEST_CASE("blend ONE/ONE adds source and destination, clamped at 1", "[raster][blend]") {
  // dst (0.25, 0.5, 0.75, 0.5) + src (0.5, 0.25, 0.5, 0.25) = (0.75, 0.75, 1.25 -> 1, 0.75)
  CHECK(blendOver({0.25f, 0.5f, 0.75f, 0.5f}, {0.5, 0.25, 0.5, 0.25}, BlendFactor::One, BlendFactor::One) ==
        glm::vec4(0.75f, 0.75f, 1.0f, 0.75f));
}

TEST_CASE("blend SRC_ALPHA/ONE_MINUS_SRC_ALPHA mixes by the source alpha", "[raster][blend]") {
  // alpha 0.25: out = 0.25 src + 0.75 dst; alpha: 0.25 * 0.25 + 0.75 * 0.5 = 0.4375
  CHECK(blendOver({1.0f, 0.0f, 0.5f, 0.5f}, {0.0, 1.0, 0.25, 0.25}, BlendFactor::SrcAlpha,
                  BlendFactor::OneMinusSrcAlpha) == glm::vec4(0.75f, 0.25f, 0.4375f, 0.4375f));
  // a non-dyadic alpha: each channel float(s * 0.3 + d * 0.7) evaluated in double
  const glm::vec4 dst(0.2f, 0.4f, 0.6f, 0.8f);
  const glm::vec4 out = blendOver(dst, {0.9, 0.1, 0.5, 0.3}, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha);
  const double src[4] = {0.9, 0.1, 0.5, 0.3};
  for (int c = 0; c < 4; ++c) CHECK(out[c] == float(src[c] * 0.3 + double(dst[c]) * (1.0 - 0.3)));
}

TEST_CASE("blend ZERO/SRC_COLOR multiplies the destination by the source", "[raster][blend]") {
  // (0.5, 0.25, 1, 0.75) * (0.5, 0.5, 0.25, 1) = (0.25, 0.125, 0.25, 0.75)
  CHECK(blendOver({0.5f, 0.25f, 1.0f, 0.75f}, {0.5, 0.5, 0.25, 1.0}, BlendFactor::Zero, BlendFactor::SrcColor) ==
        glm::vec4(0.25f, 0.125f, 0.25f, 0.75f));
}

TEST_CASE("the source colour is clamped to [0, 1] before blending", "[raster][blend]") {
  // src (2, -1, 0.5, 3) clamps to (1, 0, 0.5, 1); ZERO/SRC_COLOR then gives dst * that
  CHECK(blendOver({0.5f, 0.5f, 0.5f, 0.5f}, {2.0, -1.0, 0.5, 3.0}, BlendFactor::Zero, BlendFactor::SrcColor) ==
        glm::vec4(0.5f, 0.0f, 0.25f, 0.5f));
}

TEST_CASE("colour mask keeps the masked channels of a draw, blended or not", "[raster][blend]") {
  CHECK(blendOver({0.25f, 0.25f, 0.25f, 0.25f}, {0.5, 0.5, 0.5, 0.5}, BlendFactor::One, BlendFactor::One,
                  {true, false, true, false}) == glm::vec4(0.75f, 0.25f, 0.75f, 0.25f));
  Framebuffer fb(1, 1);
  fb.ensureColor();
  fb.color()[0] = glm::vec4(0.125f);
  RenderState s = fullViewportState(fb);
  s.colorMask = {false, true, false, true};
  Renderer r(fb);
  const ConstantColorShader shader({1.0, 0.5, 0.75, 0.25});
  draw(r, s, windowRect(s.viewport, 0, 0, 1, 1), &shader);
  CHECK(fb.colorAt(0, 0) == glm::vec4(0.125f, 0.5f, 0.125f, 0.25f));
}
