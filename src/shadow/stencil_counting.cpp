#include "shadow/stencil_counting.h"

namespace shadowref {

namespace {

// The depth/colour/stencil-test part shared by every volume pass.
RenderState countingBase(const RenderState& base) {
  RenderState s = base;
  s.depthTest = true;
  s.depthFunc = CompareFunc::Less;
  s.depthWrite = false;
  s.colorMask = {false, false, false, false};
  s.blend.enabled = false;
  s.stencilTest = true;
  return s;
}

// The face that increments: front for z-pass (entering a volume on the way to the surface), back
// for z-fail (leaving it behind the surface).
Facing incrementingFace(StencilCounting counting) {
  return counting == StencilCounting::ZPass ? FrontFacing : BackFacing;
}

}  // namespace

StencilFaceState countingFaceState(StencilCounting counting, Facing face, bool wrap) {
  StencilFaceState f;
  f.func = CompareFunc::Always;
  f.ref = 0;
  f.mask = 0xFF;
  f.writeMask = 0xFF;
  const bool increments = face == incrementingFace(counting);
  const StencilOp op = increments ? (wrap ? StencilOp::IncrWrap : StencilOp::Incr)
                                  : (wrap ? StencilOp::DecrWrap : StencilOp::Decr);
  f.sfail = StencilOp::Keep;  // never happens with ALWAYS
  f.dpfail = counting == StencilCounting::ZFail ? op : StencilOp::Keep;
  f.dppass = counting == StencilCounting::ZPass ? op : StencilOp::Keep;
  return f;
}

std::vector<RenderState> volumePassStates(const RenderState& base, StencilCounting counting,
                                          const CountingOptions& options) {
  RenderState s = countingBase(base);
  if (options.twoSided) {
    s.cull = CullMode::None;
    s.stencil[FrontFacing] = countingFaceState(counting, FrontFacing, options.wrap);
    s.stencil[BackFacing] = countingFaceState(counting, BackFacing, options.wrap);
    return {s};
  }
  // Two passes ([Kuhn 2016, §3.2], [SV slides]): each draws one kind of face, culling the other;
  // both stencil slots carry the op so the result does not depend on which slot the rasterizer
  // consults.
  const Facing first = incrementingFace(counting);
  const Facing second = first == FrontFacing ? BackFacing : FrontFacing;
  std::vector<RenderState> passes;
  for (Facing drawn : {first, second}) {
    RenderState p = s;
    p.cull = drawn == FrontFacing ? CullMode::Back : CullMode::Front;
    p.stencil[FrontFacing] = p.stencil[BackFacing] = countingFaceState(counting, drawn, options.wrap);
    passes.push_back(p);
  }
  return passes;
}

const char* name(StencilCounting counting) {
  return counting == StencilCounting::ZPass ? "zpass" : "zfail";
}

}  // namespace shadowref
