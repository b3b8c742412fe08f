// Culling x front face, scissor, colour mask, blending, clears and the accumulation buffer
// against Mesa.
#include "conformance/case_builder.h"

using namespace shadowref;
using namespace shadowref::conformance;

namespace {

constexpr int kSize = 64;

// Both windings, overlapping, with smooth colours.
void addMixedWindings(DrawStep& d) {
  const double o = 3.0 / 256;  // off the pixel-centre lattice
  addTriangle(d, {4 + o, 4, -0.2}, {60 + o, 10, 0.3}, {30 + o, 60, 0.0}, {1, 0, 0, 0.5});
  addTriangle(d, {2 + o, 40, 0.1}, {62 + o, 58, -0.4}, {44 + o, 2, 0.2}, {0, 1, 0, 0.75});
  d.vertices[1].color = {0.2, 0.9, 0.4, 0.3};
  d.vertices[5].color = {0.7, 0.1, 0.8, 1.0};
}

Scenario oneDraw(const std::string& name, const DrawStep& d) {
  Scenario sc;
  sc.name = name;
  sc.width = sc.height = kSize;
  sc.steps.push_back(d);
  return sc;
}

}  // namespace

TEST_CASE("culling of front, back or both faces with CCW or CW front face matches Mesa", "[conformance][cull]") {
  for (CullMode cull : {CullMode::Front, CullMode::Back, CullMode::FrontAndBack}) {
    for (FrontFace ff : {FrontFace::CCW, FrontFace::CW}) {
      DrawStep d;
      d.state = fullViewportState(kSize, kSize);
      d.state.cull = cull;
      d.state.frontFace = ff;
      d.state.stencilTest = true;
      for (StencilFaceState& s : d.state.stencil) s.dppass = StencilOp::Incr;
      addMixedWindings(d);
      const char* cullName = cull == CullMode::Front ? "FRONT" : cull == CullMode::Back ? "BACK" : "FRONT_AND_BACK";
      checkAgreement(runCase(oneDraw(std::string("cull ") + cullName + ", front face " +
                                         (ff == FrontFace::CCW ? "CCW" : "CW"), d)));
    }
  }
}

TEST_CASE("scissor and colour mask limit draws as in Mesa", "[conformance][scissor][colormask]") {
  DrawStep d;
  d.state = fullViewportState(kSize, kSize);
  d.state.scissorTest = true;
  d.state.scissor = Rect{7, 11, 40, 29};
  d.state.stencilTest = true;
  for (StencilFaceState& s : d.state.stencil) s.dppass = StencilOp::Incr;
  d.state.colorMask = {true, false, true, false};
  addMixedWindings(d);
  checkAgreement(runCase(oneDraw("scissor + colour mask R_B_", d)));
}

TEST_CASE("blending ONE/ONE, SRC_ALPHA/ONE_MINUS_SRC_ALPHA and ZERO/SRC_COLOR matches Mesa within 1/255 per pass",
          "[conformance][blend]") {
  struct Mode {
    const char* name;
    BlendFactor src, dst;
  };
  for (const Mode& m : {Mode{"ONE/ONE", BlendFactor::One, BlendFactor::One},
                        Mode{"SRC_ALPHA/ONE_MINUS_SRC_ALPHA", BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha},
                        Mode{"ZERO/SRC_COLOR", BlendFactor::Zero, BlendFactor::SrcColor}}) {
    Scenario sc;
    sc.name = std::string("blend ") + m.name + ", 3 passes";
    sc.width = sc.height = kSize;
    // Mesa rounds to 8 bits after the clear and after every pass, shadowref keeps float.
    sc.colorTolerance255 = 4;
    ClearStep c;
    c.state = fullViewportState(kSize, kSize);
    c.color = true;
    c.colorValue = {0.25f, 0.5f, 0.75f, 1.0f};
    sc.steps.push_back(c);
    for (int pass = 0; pass < 3; ++pass) {
      DrawStep d;
      d.state = fullViewportState(kSize, kSize);
      d.state.blend = BlendState{true, m.src, m.dst};
      addMixedWindings(d);
      for (ColoredVertex& v : d.vertices) v.color *= glm::dvec4(0.3, 0.3, 0.3, 1.0);
      sc.steps.push_back(d);
    }
    checkAgreement(runCase(sc));
  }
}

TEST_CASE("clears honour the scissor box, colour mask, depth mask and front stencil write mask as in Mesa",
          "[conformance][clear]") {
  Scenario sc;
  sc.name = "clears with scissor and masks";
  sc.width = sc.height = kSize;
  ClearStep all;
  all.state = fullViewportState(kSize, kSize);
  all.color = all.depth = all.stencil = true;
  all.colorValue = {0.1f, 0.2f, 0.3f, 0.4f};
  all.depthValue = 0.75;
  all.stencilValue = 0x3C;
  sc.steps.push_back(all);
  ClearStep masked = all;
  masked.state.scissorTest = true;
  masked.state.scissor = Rect{10, 5, 30, 40};
  masked.state.colorMask = {false, true, false, true};
  masked.state.stencil[FrontFacing].writeMask = 0x0F;
  masked.colorValue = {0.9f, 0.8f, 0.7f, 0.6f};
  masked.depthValue = 0.25;
  masked.stencilValue = 0xFF;
  sc.steps.push_back(masked);
  ClearStep noDepth = masked;
  noDepth.state.scissor = Rect{30, 20, 30, 40};
  noDepth.state.depthWrite = false;  // the depth mask stops the depth clear
  noDepth.depthValue = 0.0;
  sc.steps.push_back(noDepth);
  checkAgreement(runCase(sc));
}

TEST_CASE("the accumulation ops ACCUM, LOAD, RETURN, MULT and ADD return Mesa's colour within 1/255",
          "[conformance][accum]") {
  Scenario sc;
  sc.name = "accumulation LOAD, ACCUM, MULT, ADD, RETURN";
  sc.width = sc.height = kSize;
  sc.colorTolerance255 = 1;
  const RenderState full = fullViewportState(kSize, kSize);
  DrawStep first;
  first.state = full;
  addMixedWindings(first);
  sc.steps.push_back(first);
  sc.steps.push_back(AccumStep{full, AccumOp::Load, 0.5f});
  ClearStep clear;
  clear.state = full;
  clear.color = true;
  clear.colorValue = {0.2f, 0.6f, 0.4f, 0.8f};
  sc.steps.push_back(clear);
  sc.steps.push_back(AccumStep{full, AccumOp::Accum, 0.5f});
  sc.steps.push_back(AccumStep{full, AccumOp::Mult, 0.8f});
  sc.steps.push_back(AccumStep{full, AccumOp::Add, 0.1f});
  RenderState returnState = full;
  returnState.scissorTest = true;
  returnState.scissor = Rect{4, 8, 50, 50};
  returnState.colorMask = {true, true, false, true};
  sc.steps.push_back(AccumStep{returnState, AccumOp::Return, 1.25f});
  checkAgreement(runCase(sc));
}
