#include "conformance/osmesa_harness.h"

#include <GL/osmesa.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>

namespace shadowref::conformance {

namespace {

// GL 1.2+ entry points are loaded through OSMesaGetProcAddress rather than relying on exported
// prototypes (gl.h declares only GL 1.1 without GL_GLEXT_PROTOTYPES).
struct GlExtensions {
  PFNGLSTENCILFUNCSEPARATEPROC stencilFuncSeparate = nullptr;
  PFNGLSTENCILOPSEPARATEPROC stencilOpSeparate = nullptr;
  PFNGLSTENCILMASKSEPARATEPROC stencilMaskSeparate = nullptr;
};

template <class Fn>
Fn load(const char* name) {
  auto fn = reinterpret_cast<Fn>(OSMesaGetProcAddress(name));
  if (!fn) throw std::runtime_error(std::string("OSMesa lacks ") + name);
  return fn;
}

// One context per size, made current for each scenario; created lazily and kept for the process.
class MesaContext {
 public:
  MesaContext(int width, int height) : width_(width), height_(height), pixels_(size_t(width) * height * 4) {
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 16, nullptr);
    if (!context_) throw std::runtime_error("OSMesaCreateContextExt failed");
    makeCurrent();
    gl_.stencilFuncSeparate = load<PFNGLSTENCILFUNCSEPARATEPROC>("glStencilFuncSeparate");
    gl_.stencilOpSeparate = load<PFNGLSTENCILOPSEPARATEPROC>("glStencilOpSeparate");
    gl_.stencilMaskSeparate = load<PFNGLSTENCILMASKSEPARATEPROC>("glStencilMaskSeparate");
    GLint depthBits = 0, stencilBits = 0, accumBits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depthBits);
    glGetIntegerv(GL_STENCIL_BITS, &stencilBits);
    glGetIntegerv(GL_ACCUM_RED_BITS, &accumBits);
    if (depthBits != 24 || stencilBits != 8 || accumBits < 16)
      throw std::runtime_error("OSMesa context lacks 24-bit depth, 8-bit stencil or a 16-bit accumulation buffer");
  }
  ~MesaContext() { OSMesaDestroyContext(context_); }
  MesaContext(const MesaContext&) = delete;
  MesaContext& operator=(const MesaContext&) = delete;

  void makeCurrent() {
    if (!OSMesaMakeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, width_, height_))
      throw std::runtime_error("OSMesaMakeCurrent failed");
  }
  const GlExtensions& gl() const { return gl_; }

 private:
  int width_, height_;
  std::vector<unsigned char> pixels_;
  OSMesaContext context_ = nullptr;
  GlExtensions gl_;
};

MesaContext& contextFor(int width, int height) {
  static std::map<std::pair<int, int>, std::unique_ptr<MesaContext>> contexts;
  auto& slot = contexts[{width, height}];
  if (!slot) slot = std::make_unique<MesaContext>(width, height);
  slot->makeCurrent();
  return *slot;
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

void enable(GLenum cap, bool on) { on ? glEnable(cap) : glDisable(cap); }

// Every field of RenderState, as GL state. RenderState::clipFar has no GL counterpart (GL always
// clips at the far plane unless depth clamp is on); cases with clipFar off are built so that
// nothing lies beyond the far plane.
void applyState(const RenderState& s, const GlExtensions& gl) {
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
    gl.stencilFuncSeparate(faces[f], glCompare(st.func), st.ref, st.mask);
    gl.stencilOpSeparate(faces[f], glStencilOpOf(st.sfail), glStencilOpOf(st.dpfail), glStencilOpOf(st.dppass));
    gl.stencilMaskSeparate(faces[f], st.writeMask);
  }

  enable(GL_BLEND, s.blend.enabled);
  glBlendFunc(glBlendFactorOf(s.blend.src), glBlendFactorOf(s.blend.dst));
  glColorMask(s.colorMask[0], s.colorMask[1], s.colorMask[2], s.colorMask[3]);
}

void execute(const DrawStep& d, const GlExtensions& gl) {
  applyState(d.state, gl);
  glBegin(GL_TRIANGLES);
  for (const ColoredVertex& v : d.vertices) {
    glColor4d(v.color.r, v.color.g, v.color.b, v.color.a);
    glVertex4d(v.clip.x, v.clip.y, v.clip.z, v.clip.w);
  }
  glEnd();
}

void execute(const ClearStep& c, const GlExtensions& gl) {
  applyState(c.state, gl);
  glClearColor(c.colorValue.r, c.colorValue.g, c.colorValue.b, c.colorValue.a);
  glClearDepth(c.depthValue);
  glClearStencil(c.stencilValue);
  glClearAccum(c.accumValue.r, c.accumValue.g, c.accumValue.b, c.accumValue.a);
  GLbitfield bits = 0;
  if (c.color) bits |= GL_COLOR_BUFFER_BIT;
  if (c.depth) bits |= GL_DEPTH_BUFFER_BIT;
  if (c.stencil) bits |= GL_STENCIL_BUFFER_BIT;
  if (c.accum) bits |= GL_ACCUM_BUFFER_BIT;
  glClear(bits);
}

void execute(const AccumStep& a, const GlExtensions& gl) {
  applyState(a.state, gl);
  glAccum(glAccumOpOf(a.op), a.value);
}

Readback readBack(int width, int height) {
  Readback r;
  r.width = width;
  r.height = height;
  const size_t n = size_t(width) * size_t(height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<unsigned char> rgba(n * 4);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  r.color.resize(n);
  for (size_t i = 0; i < n; ++i)
    r.color[i] = glm::vec4(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], rgba[4 * i + 3]) / 255.0f;
  std::vector<GLuint> depth(n);
  glReadPixels(0, 0, width, height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depth.data());
  r.depth24.resize(n);
  for (size_t i = 0; i < n; ++i) r.depth24[i] = depth[i] >> 8;  // 32-bit scaled value -> 24 bits
  r.stencil.resize(n);
  glReadPixels(0, 0, width, height, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, r.stencil.data());
  return r;
}

}  // namespace

Readback renderWithMesa(const Scenario& scenario) {
  MesaContext& context = contextFor(scenario.width, scenario.height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glShadeModel(GL_SMOOTH);
  glDisable(GL_LIGHTING);
  glDisable(GL_DITHER);  // dithering would perturb the 8-bit colour by up to one unit

  ClearStep initial;
  initial.state = fullViewportState(scenario.width, scenario.height);
  initial.color = initial.depth = initial.stencil = initial.accum = true;
  execute(initial, context.gl());
  for (const Step& step : scenario.steps) std::visit([&](const auto& s) { execute(s, context.gl()); }, step);
  glFinish();
  if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error in scenario " + scenario.name);
  return readBack(scenario.width, scenario.height);
}

std::string mesaRenderer() {
  contextFor(8, 8);
  const GLubyte* renderer = glGetString(GL_RENDERER);
  return renderer ? reinterpret_cast<const char*>(renderer) : "unknown";
}

std::string mesaDriverName() {
  const std::string r = mesaRenderer();
  for (const char* known : {"softpipe", "llvmpipe"})
    if (r.find(known) != std::string::npos) return known;
  return r;
}

}  // namespace shadowref::conformance
