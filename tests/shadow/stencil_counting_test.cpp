#include <catch2/catch.hpp>

#include "shadow/stencil_counting.h"

using namespace shadowref;

namespace {

RenderState baseState() {
  RenderState s;
  s.viewport = {0, 0, 200, 160, 0.0, 1.0};
  s.clipFar = false;
  s.colorMask = {true, true, true, true};
  s.depthWrite = true;
  s.blend = {true, BlendFactor::One, BlendFactor::One};
  return s;
}

StencilFaceState face(StencilOp dpfail, StencilOp dppass) {
  StencilFaceState f;
  f.func = CompareFunc::Always;
  f.ref = 0;
  f.mask = 0xFF;
  f.writeMask = 0xFF;
  f.sfail = StencilOp::Keep;
  f.dpfail = dpfail;
  f.dppass = dppass;
  return f;
}

bool sameFace(const StencilFaceState& a, const StencilFaceState& b) {
  return a.func == b.func && a.ref == b.ref && a.mask == b.mask && a.writeMask == b.writeMask &&
         a.sfail == b.sfail && a.dpfail == b.dpfail && a.dppass == b.dppass;
}

// Depth LESS without writes, no colour, stencil on; everything else from the base.
void checkCountingBase(const RenderState& s) {
  CHECK(s.depthTest);
  CHECK(s.depthFunc == CompareFunc::Less);
  CHECK_FALSE(s.depthWrite);
  CHECK(s.colorMask == std::array<bool, 4>{false, false, false, false});
  CHECK_FALSE(s.blend.enabled);
  CHECK(s.stencilTest);
  CHECK(s.viewport.width == 200);
  CHECK(s.viewport.height == 160);
  CHECK_FALSE(s.clipFar);
}

constexpr auto K = StencilOp::Keep;

}  // namespace

TEST_CASE("stencil counting: z-pass two-sided — front INCR_WRAP on depth pass, back DECR_WRAP ([Kuhn 2016, §3.2])",
          "[volumes][stencil_counting]") {
  const auto states = volumePassStates(baseState(), StencilCounting::ZPass, {true, true});
  REQUIRE(states.size() == 1);
  checkCountingBase(states[0]);
  CHECK(states[0].cull == CullMode::None);
  CHECK(sameFace(states[0].stencil[FrontFacing], face(K, StencilOp::IncrWrap)));
  CHECK(sameFace(states[0].stencil[BackFacing], face(K, StencilOp::DecrWrap)));
}

TEST_CASE("stencil counting: z-fail two-sided — back INCR_WRAP on depth fail, front DECR_WRAP (Carmack)",
          "[volumes][stencil_counting]") {
  const auto states = volumePassStates(baseState(), StencilCounting::ZFail, {true, true});
  REQUIRE(states.size() == 1);
  checkCountingBase(states[0]);
  CHECK(states[0].cull == CullMode::None);
  CHECK(sameFace(states[0].stencil[BackFacing], face(StencilOp::IncrWrap, K)));
  CHECK(sameFace(states[0].stencil[FrontFacing], face(StencilOp::DecrWrap, K)));
}

TEST_CASE("stencil counting: z-pass in two culled passes, saturating — front faces INCR first, then back DECR ([SV slides])",
          "[volumes][stencil_counting]") {
  const auto states = volumePassStates(baseState(), StencilCounting::ZPass, {false, false});
  REQUIRE(states.size() == 2);
  for (const RenderState& s : states) checkCountingBase(s);
  CHECK(states[0].cull == CullMode::Back);
  CHECK(sameFace(states[0].stencil[FrontFacing], face(K, StencilOp::Incr)));
  CHECK(sameFace(states[0].stencil[BackFacing], face(K, StencilOp::Incr)));
  CHECK(states[1].cull == CullMode::Front);
  CHECK(sameFace(states[1].stencil[FrontFacing], face(K, StencilOp::Decr)));
  CHECK(sameFace(states[1].stencil[BackFacing], face(K, StencilOp::Decr)));
}

TEST_CASE("stencil counting: z-fail in two culled passes — back faces INCR_WRAP on fail first, then front DECR_WRAP ([SV slides])",
          "[volumes][stencil_counting]") {
  const auto states = volumePassStates(baseState(), StencilCounting::ZFail, {false, true});
  REQUIRE(states.size() == 2);
  for (const RenderState& s : states) checkCountingBase(s);
  CHECK(states[0].cull == CullMode::Front);
  CHECK(sameFace(states[0].stencil[BackFacing], face(StencilOp::IncrWrap, K)));
  CHECK(sameFace(states[0].stencil[FrontFacing], face(StencilOp::IncrWrap, K)));
  CHECK(states[1].cull == CullMode::Back);
  CHECK(sameFace(states[1].stencil[FrontFacing], face(StencilOp::DecrWrap, K)));
  CHECK(sameFace(states[1].stencil[BackFacing], face(StencilOp::DecrWrap, K)));
}

TEST_CASE("stencil counting: z-fail saturating uses INCR / DECR on depth fail", "[volumes][stencil_counting]") {
  CHECK(sameFace(countingFaceState(StencilCounting::ZFail, BackFacing, false), face(StencilOp::Incr, K)));
  CHECK(sameFace(countingFaceState(StencilCounting::ZFail, FrontFacing, false), face(StencilOp::Decr, K)));
  CHECK(sameFace(countingFaceState(StencilCounting::ZPass, FrontFacing, false), face(K, StencilOp::Incr)));
  CHECK(sameFace(countingFaceState(StencilCounting::ZPass, BackFacing, false), face(K, StencilOp::Decr)));
}
