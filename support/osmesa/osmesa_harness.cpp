#include "osmesa/osmesa_harness.h"
#include "trace/osmesa/gl_state.h"

#include <GL/osmesa.h>

#include <map>
#include <memory>
#include <stdexcept>
#include <tuple>

namespace shadowref::conformance {

namespace {

// One context per size, made current for each scenario; created lazily and kept for the process.
class MesaContext {
 public:
  MesaContext(int width, int height) : width_(width), height_(height), pixels_(size_t(width) * height * 4) {
    context_ = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 16, nullptr);
    if (!context_) throw std::runtime_error("OSMesaCreateContextExt failed");
    makeCurrent();
    gl_ = GlStencilFunctions::load();
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
  const GlStencilFunctions& gl() const { return gl_; }

 private:
  int width_, height_;
  std::vector<unsigned char> pixels_;
  OSMesaContext context_ = nullptr;
  GlStencilFunctions gl_;
};

MesaContext& contextFor(int width, int height) {
  static std::map<std::pair<int, int>, std::unique_ptr<MesaContext>> contexts;
  auto& slot = contexts[{width, height}];
  if (!slot) slot = std::make_unique<MesaContext>(width, height);
  slot->makeCurrent();
  return *slot;
}

void execute(const DrawStep& d, const GlStencilFunctions& gl) {
  applyRenderState(d.state, gl);
  glBegin(GL_TRIANGLES);
  for (const ColoredVertex& v : d.vertices) {
    glColor4d(v.color.r, v.color.g, v.color.b, v.color.a);
    glVertex4d(v.clip.x, v.clip.y, v.clip.z, v.clip.w);
  }
  glEnd();
}

void execute(const ClearStep& c, const GlStencilFunctions& gl) {
  applyRenderState(c.state, gl);
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

void execute(const AccumStep& a, const GlStencilFunctions& gl) {
  applyRenderState(a.state, gl);
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
