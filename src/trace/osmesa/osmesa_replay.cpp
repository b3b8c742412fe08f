#include "trace/osmesa/osmesa_replay.h"

#include <cstdlib>
#include <stdexcept>

namespace shadowref::trace {

namespace {

std::string& lastRenderer() {
  static std::string renderer;
  return renderer;
}

void execute(const ClearCommand& c, const conformance::GlStencilFunctions& gl) {
  const ClearRequest& q = c.request;
  conformance::applyRenderState(q.state, gl);
  GLbitfield bits = 0;
  if (q.color) {
    glClearColor(q.color->r, q.color->g, q.color->b, q.color->a);
    bits |= GL_COLOR_BUFFER_BIT;
  }
  if (q.depth) {
    glClearDepth(*q.depth);
    bits |= GL_DEPTH_BUFFER_BIT;
  }
  if (q.stencil) {
    glClearStencil(*q.stencil);
    bits |= GL_STENCIL_BUFFER_BIT;
  }
  if (q.accum) {
    glClearAccum(q.accum->r, q.accum->g, q.accum->b, q.accum->a);
    bits |= GL_ACCUM_BUFFER_BIT;
  }
  glClear(bits);
}

void execute(const DrawCommand& d, const FragmentShader* shader, const conformance::GlStencilFunctions& gl) {
  conformance::applyRenderState(d.state, gl);
  const std::vector<ClipVertex> v = fixedFunctionVertices(d, shader);
  // A draw without a shader writes no colour (RenderState's colour mask stays as it is for the
  // shadowref side, which draws no colour at all).
  if (!shader) glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  glBegin(GL_TRIANGLES);
  const auto vertex = [&](size_t i) {
    const ClipVertex& p = v[i];
    if (shader) glColor4d(p.varyings[0], p.varyings[1], p.varyings[2], p.varyings[3]);
    glVertex4d(p.position.x, p.position.y, p.position.z, p.position.w);
  };
  if (d.indices.empty()) {
    for (size_t i = 0; i + 2 < v.size(); i += 3)
      for (size_t k = 0; k < 3; ++k) vertex(i + k);
  } else {
    for (uint32_t i : d.indices) vertex(i);
  }
  glEnd();
}

Buffers readBack(const Target& t) {
  Buffers b;
  b.width = t.width;
  b.height = t.height;
  b.depthFormat = DepthFormat::Unorm24;
  const size_t n = size_t(t.width) * size_t(t.height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  std::vector<unsigned char> rgba(n * 4);
  glReadPixels(0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  b.color.resize(n);
  for (size_t i = 0; i < n; ++i)
    b.color[i] = glm::vec4(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], rgba[4 * i + 3]) / 255.0f;
  std::vector<GLuint> depth(n);
  glReadPixels(0, 0, t.width, t.height, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, depth.data());
  b.depth.resize(n);
  for (size_t i = 0; i < n; ++i) b.depth[i] = depth[i] >> 8;  // 32-bit scaled value -> 24 bits
  b.stencil.resize(n);
  glReadPixels(0, 0, t.width, t.height, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE, b.stencil.data());
  return b;
}

bool usesAccumulation(const Trace& trace, uint32_t target) {
  for (const Command& c : trace.commands) {
    if (c.target != target) continue;
    if (std::holds_alternative<AccumCommand>(c.what)) return true;
    if (const auto* clear = std::get_if<ClearCommand>(&c.what); clear && clear->request.accum) return true;
  }
  return false;
}

}  // namespace

void GlContext::loadCommon() {
  const GLubyte* r = glGetString(GL_RENDERER);
  renderer_ = r ? reinterpret_cast<const char*>(r) : "unknown";
  lastRenderer() = renderer_;
  stencil_ = conformance::GlStencilFunctions::load();
}

OsmesaContext::OsmesaContext(int width, int height)
    : width_(width), height_(height), pixels_(size_t(width) * size_t(height) * 4) {
  context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 16, nullptr);
  if (!context_) throw std::runtime_error("OSMesaCreateContextExt failed");
  try {
    makeCurrent();
    GLint depthBits = 0, stencilBits = 0, accumBits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depthBits);
    glGetIntegerv(GL_STENCIL_BITS, &stencilBits);
    glGetIntegerv(GL_ACCUM_RED_BITS, &accumBits);
    if (depthBits != 24 || stencilBits != 8 || accumBits < 16)
      throw std::runtime_error("the OSMesa context lacks 24-bit depth, 8-bit stencil or a 16-bit accumulation buffer");
    loadCommon();
  } catch (...) {
    OSMesaDestroyContext(context_);
    throw;
  }
}

OsmesaContext::~OsmesaContext() { OSMesaDestroyContext(context_); }

void OsmesaContext::makeCurrent() {
  if (!OSMesaMakeCurrent(context_, pixels_.data(), GL_UNSIGNED_BYTE, width_, height_))
    throw std::runtime_error("OSMesaMakeCurrent failed");
}

void setFixedFunctionDefaults() {
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glShadeModel(GL_SMOOTH);
  glDisable(GL_LIGHTING);
  glDisable(GL_DITHER);
}

ReplayResult replayOnGl(const Trace& trace, const std::string& driver,
                        const std::function<std::unique_ptr<GlContext>(int width, int height)>& make) {
  // Mesa reads GALLIUM_DRIVER when it makes its first context; a process asking for another
  // driver later is refused below.
  setenv("GALLIUM_DRIVER", driver.c_str(), 1);
  const ReplayShaders shaders(trace);
  ReplayResult result;
  for (uint32_t t = 0; t < trace.targets.size(); ++t) {
    const Target& target = trace.targets[t];
    const std::unique_ptr<GlContext> context = make(target.width, target.height);
    if (context->renderer().find(driver) == std::string::npos)
      throw std::runtime_error("asked for Mesa's " + driver + ", got '" + context->renderer() + "'");
    if (!context->hasAccumulation() && usesAccumulation(trace, t))
      throw std::runtime_error("framebuffer " + std::to_string(t) +
                               " uses the accumulation buffer, which this GL's framebuffer lacks");
    setFixedFunctionDefaults();
    // GL leaves a new context's buffers undefined; shadowref's start as colour 0, depth 1,
    // stencil 0, accumulation 0 (Framebuffer::ensure*).
    RenderState full;
    full.viewport = Viewport{0, 0, target.width, target.height, 0.0, 1.0};
    conformance::applyRenderState(full, context->stencil());
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClearStencil(0);
    GLbitfield initial = GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT;
    if (context->hasAccumulation()) {
      glClearAccum(0, 0, 0, 0);
      initial |= GL_ACCUM_BUFFER_BIT;
    }
    glClear(initial);
    for (const Command& c : trace.commands) {
      if (c.target != t) continue;
      if (const auto* clear = std::get_if<ClearCommand>(&c.what)) {
        execute(*clear, context->stencil());
      } else if (const auto* d = std::get_if<DrawCommand>(&c.what)) {
        execute(*d, d->shader == kNoShader ? nullptr : &shaders[d->shader], context->stencil());
      } else if (const auto* a = std::get_if<AccumCommand>(&c.what)) {
        conformance::applyRenderState(a->state, context->stencil());
        glAccum(conformance::glAccumOpOf(a->op), a->value);
      }
    }
    glFinish();
    if (const GLenum e = glGetError(); e != GL_NO_ERROR)
      throw std::runtime_error("GL error " + std::to_string(e) + " while replaying framebuffer " + std::to_string(t));
    result.buffers.push_back(readBack(target));
  }
  return result;
}

ReplayResult replayOnOsmesa(const Trace& trace, const std::string& driver) {
  return replayOnGl(trace, driver, [](int width, int height) { return std::make_unique<OsmesaContext>(width, height); });
}

std::string osmesaRenderer() { return lastRenderer(); }

}  // namespace shadowref::trace
