#include "trace/osmesa/gl_state.h"

namespace shadowref::conformance {

namespace {
void enable(GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); }
}  // namespace

GlStencilFunctions GlStencilFunctions::load() {
  GlStencilFunctions f;
  f.funcSeparate = loadGlFunction<PFNGLSTENCILFUNCSEPARATEPROC>("glStencilFuncSeparate");
  f.opSeparate = loadGlFunction<PFNGLSTENCILOPSEPARATEPROC>("glStencilOpSeparate");
  f.maskSeparate = loadGlFunction<PFNGLSTENCILMASKSEPARATEPROC>("glStencilMaskSeparate");
  return f;
}

GLenum glCompare(CompareFunc f) {
  switch (f) {
    case CompareFunc::Never: return GL_NEVER;
    case CompareFunc::Less: return GL_LESS;
    case CompareFunc::Equal: return GL_EQUAL;
    case CompareFunc::LEqual: return GL_LEQUAL;
    case CompareFunc::Greater: return GL_GREATER;
    case CompareFunc::NotEqual: return GL_NOTEQUAL;
    case CompareFunc::GEqual: return GL_GEQUAL;
    case CompareFunc::Always: return GL_ALWAYS;
  }
  throw std::logic_error("bad CompareFunc");
}

GLenum glStencilOpOf(StencilOp op) {
  switch (op) {
    case StencilOp::Keep: return GL_KEEP;
    case StencilOp::Zero: return GL_ZERO;
    case StencilOp::Replace: return GL_REPLACE;
    case StencilOp::Incr: return GL_INCR;
    case StencilOp::Decr: return GL_DECR;
    case StencilOp::Invert: return GL_INVERT;
    case StencilOp::IncrWrap: return GL_INCR_WRAP;
    case StencilOp::DecrWrap: return GL_DECR_WRAP;
  }
  throw std::logic_error("bad StencilOp");
}

GLenum glBlendFactorOf(BlendFactor f) {
  switch (f) {
    case BlendFactor::Zero: return GL_ZERO;
    case BlendFactor::One: return GL_ONE;
    case BlendFactor::SrcColor: return GL_SRC_COLOR;
    case BlendFactor::OneMinusSrcColor: return GL_ONE_MINUS_SRC_COLOR;
    case BlendFactor::DstColor: return GL_DST_COLOR;
    case BlendFactor::OneMinusDstColor: return GL_ONE_MINUS_DST_COLOR;
    case BlendFactor::SrcAlpha: return GL_SRC_ALPHA;
    case BlendFactor::OneMinusSrcAlpha: return GL_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::DstAlpha: return GL_DST_ALPHA;
    case BlendFactor::OneMinusDstAlpha: return GL_ONE_MINUS_DST_ALPHA;
  }
  throw std::logic_error("bad BlendFactor");
}

GLenum glAccumOpOf(AccumOp op) {
  switch (op) {
    case AccumOp::Accum: return GL_ACCUM;
    case AccumOp::Load: return GL_LOAD;
    case AccumOp::Return: return GL_RETURN;
    case AccumOp::Mult: return GL_MULT;
    case AccumOp::Add: return GL_ADD;
  }
  throw std::logic_error("bad AccumOp");
}


void applyRenderState(const RenderState& s, const GlStencilFunctions& gl) {
  glViewport(s.viewport.x, s.viewport.y, s.viewport.width, s.viewport.height);
  glDepthRange(s.viewport.nearVal, s.viewport.farVal);
  enable(GL_SCISSOR_TEST, s.scissorTest);
  glScissor(s.scissor.x, s.scissor.y, s.scissor.width, s.scissor.height);

  enable(GL_CULL_FACE, s.cull != CullMode::None);
  glCullFace(s.cull == CullMode::Front ? GL_FRONT : s.cull == CullMode::Back ? GL_BACK : GL_FRONT_AND_BACK);
  glFrontFace(s.frontFace == FrontFace::CCW ? GL_CCW : GL_CW);

  enable(GL_DEPTH_TEST, s.depthTest);
  glDepthFunc(glCompare(s.depthFunc));
  glDepthMask(s.depthWrite ? GL_TRUE : GL_FALSE);
  enable(GL_DEPTH_CLAMP, s.depthClamp);
  enable(GL_POLYGON_OFFSET_FILL, s.polygonOffset.enabled);
  glPolygonOffset(GLfloat(s.polygonOffset.factor), GLfloat(s.polygonOffset.units));

  enable(GL_STENCIL_TEST, s.stencilTest);
  const GLenum faces[2] = {GL_FRONT, GL_BACK};
  for (int f = 0; f < 2; ++f) {
    const StencilFaceState& st = s.stencil[f];
    gl.funcSeparate(faces[f], glCompare(st.func), st.ref, st.mask);
    gl.opSeparate(faces[f], glStencilOpOf(st.sfail), glStencilOpOf(st.dpfail), glStencilOpOf(st.dppass));
    gl.maskSeparate(faces[f], st.writeMask);
  }

  enable(GL_BLEND, s.blend.enabled);
  glBlendFunc(glBlendFactorOf(s.blend.src), glBlendFactorOf(s.blend.dst));
  glColorMask(s.colorMask[0], s.colorMask[1], s.colorMask[2], s.colorMask[3]);
}

}  // namespace shadowref::conformance
