#include "conformance/shadowref_backend.h"

#include "gl/accumulation.h"
#include "gl/clear.h"
#include "gl/fragment_shader.h"
#include "gl/framebuffer.h"
#include "exec/renderer.h"

namespace shadowref::conformance {

namespace {

void execute(Renderer& renderer, const DrawStep& d) {
  std::vector<ClipVertex> vertices(d.vertices.size());
  for (size_t i = 0; i < d.vertices.size(); ++i) {
    // GL's vertex pipeline is float: both implementations get the same float clip coordinates.
    vertices[i].position = glm::dvec4(glm::vec4(d.vertices[i].clip));
    for (int c = 0; c < 4; ++c) vertices[i].varyings[size_t(c)] = d.vertices[i].color[c];
  }
  static const ColorVaryingShader shader;
  DrawCall call;
  call.state = &d.state;
  call.vertices = vertices;
  call.shader = &shader;
  renderer.draw(call);
}

void execute(Renderer& renderer, const ClearStep& c) {
  Framebuffer& fb = renderer.framebuffer();
  if (c.color) clearColor(fb, c.state, c.colorValue);
  if (c.depth) clearDepth(fb, c.state, c.depthValue);
  if (c.stencil) clearStencil(fb, c.state, c.stencilValue);
  if (c.accum) clearAccum(fb, c.state, c.accumValue);
}

void execute(Renderer& renderer, const AccumStep& a) { accumulate(renderer.framebuffer(), a.state, a.op, a.value); }

}  // namespace

Readback renderWithShadowref(const Scenario& scenario) {
  Framebuffer fb(scenario.width, scenario.height, DepthFormat::Unorm24);
  Renderer renderer(fb);
  ClearStep initial;
  initial.state = fullViewportState(scenario.width, scenario.height);
  initial.color = initial.depth = initial.stencil = initial.accum = true;
  execute(renderer, initial);
  for (const Step& step : scenario.steps) std::visit([&](const auto& s) { execute(renderer, s); }, step);

  Readback r;
  r.width = fb.width();
  r.height = fb.height();
  r.color.assign(fb.color().begin(), fb.color().end());
  r.depth24.assign(fb.depthCodes().begin(), fb.depthCodes().end());  // Unorm24 codes are the 24-bit values
  r.stencil.assign(fb.stencil().begin(), fb.stencil().end());
  return r;
}

}  // namespace shadowref::conformance
