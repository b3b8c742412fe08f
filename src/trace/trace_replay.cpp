#include "trace/trace_replay.h"

#include <algorithm>
#include <stdexcept>

#include "gl/lighting.h"
#include "gl/shader_description.h"
#include "shadow/light_shadow.h"
#include "shadow/shadow_map_renderer.h"

namespace shadowref::trace {

struct ReplayShaders::Owned {
  std::vector<std::unique_ptr<LightShadow>> shadows;
};

namespace {

ShadowLookup lookupOf(const ShadowMapDescription& m) {
  ShadowLookup l;
  l.textureMatrix = m.textureMatrix;
  l.sampler.texture = m.texture;
  l.sampler.func = m.func;
  l.sampler.failValue = m.failValue;
  l.pcf = m.pcf;
  l.constantBias = m.constantBias;
  l.outsideLit = m.outsideLit;
  l.receiverPlaneBias = ReceiverPlaneBias(m.receiverPlaneBias);
  return l;
}

std::unique_ptr<LightShadow> lightShadowOf(const LightShadowDescription& d) {
  auto s = std::make_unique<LightShadow>();
  s->cube = d.cube;
  if (d.cube) {
    s->cubeLookup.lightPosition = d.lightPosition;
    for (size_t f = 0; f < 6; ++f) s->cubeLookup.faces[f] = lookupOf(d.maps.at(f));
  } else {
    s->lookup = lookupOf(d.maps.at(0));
  }
  s->trapezoidal = d.trapezoidal;
  s->views[0].view = d.lightView;
  s->views[0].projection = d.lightProjection;
  return s;
}

}  // namespace

ReplayShaders::ReplayShaders(const Trace& trace) {
  for (const Shader& shader : trace.shaders) {
    const ShaderDescription& d = shader.description;
    switch (d.kind) {
      case ShaderKind::Constant: shaders_.push_back(std::make_unique<ConstantColorShader>(d.color)); break;
      case ShaderKind::ColorVarying: shaders_.push_back(std::make_unique<ColorVaryingShader>()); break;
      case ShaderKind::Gouraud: shaders_.push_back(std::make_unique<GouraudShader>()); break;
      case ShaderKind::PerPixelLighting: shaders_.push_back(std::make_unique<PerPixelLightingShader>(d.setup)); break;
      case ShaderKind::ShadowMapped:
      case ShaderKind::ShadowMappedGouraud: {
        auto& owned = owned_.emplace_back(std::make_unique<Owned>());
        std::vector<const LightShadow*> shadows;
        for (const LightShadowDescription& s : d.shadows) shadows.push_back(owned->shadows.emplace_back(lightShadowOf(s)).get());
        shaders_.push_back(d.kind == ShaderKind::ShadowMapped ? makeShadowMappedShader(d.setup, std::move(shadows))
                                                              : makeShadowMappedGouraudShader(std::move(shadows)));
        break;
      }
    }
  }
}

ReplayShaders::~ReplayShaders() = default;

namespace {

// The clip position, and a colour channel, as GL's float vertex pipeline holds them. Every
// double -> float -> double round trip of the replay narrows through these, and they are not
// inlined and return the floats, so the widening happens after the call: GCC 12.2's SLP
// vectorizer compiles glm::dvec4(glm::vec4(p)) as a plain copy of the doubles when it sees both
// conversions in one function (with -march=x86-64-v3 or v4, the build's; glm::dvec2(glm::vec2(p))
// even at plain -O2), so the replay drew unrounded positions.
[[gnu::noinline]] glm::vec4 toFloat(const glm::dvec4& p) { return glm::vec4(p); }
[[gnu::noinline]] float toFloat(double x) { return float(x); }

}  // namespace

std::vector<ClipVertex> fixedFunctionVertices(const DrawCommand& draw, const FragmentShader* shader) {
  std::vector<ClipVertex> out(draw.vertices.size());
  for (size_t i = 0; i < out.size(); ++i) {
    const ClipVertex& v = draw.vertices[i];
    out[i].position = glm::dvec4(toFloat(v.position));
    if (!shader) continue;
    FragmentInput in;
    in.facing = FrontFacing;
    in.varyings = v.varyings.data();
    const glm::dvec4 c = shader->shade(in);
    for (int k = 0; k < 4; ++k) {
      // NaN (a shader's 0/0) becomes 0, as the clamp of a colour write makes it.
      const double clamped = c[k] > 0.0 ? std::min(c[k], 1.0) : 0.0;
      out[i].varyings[size_t(k)] = double(toFloat(clamped));
    }
  }
  return out;
}

void forEachTriangle(const DrawCommand& draw,
                     const std::function<void(const glm::dvec4&, const glm::dvec4&, const glm::dvec4&)>& f) {
  if (draw.indices.empty()) {
    for (size_t i = 0; i + 2 < draw.vertices.size(); i += 3)
      f(draw.vertices[i].position, draw.vertices[i + 1].position, draw.vertices[i + 2].position);
    return;
  }
  for (size_t i = 0; i + 2 < draw.indices.size(); i += 3)
    f(draw.vertices[draw.indices[i]].position, draw.vertices[draw.indices[i + 1]].position,
      draw.vertices[draw.indices[i + 2]].position);
}

ReplayResult replayOnShadowref(const Trace& trace, PipelineKind kind, int threads, ReplayMode mode) {
  const ReplayShaders shaders(trace);
  static const ColorVaryingShader vertexColours;
  const std::unique_ptr<PipelineMaker> maker = makePipelineMaker(kind, threads);
  if (!maker) throw std::runtime_error(std::string("the ") + name(kind) + " pipeline is not available in this build");
  std::vector<std::unique_ptr<Framebuffer>> framebuffers;
  std::vector<std::unique_ptr<Pipeline>> pipelines;
  for (const Target& t : trace.targets) {
    framebuffers.push_back(std::make_unique<Framebuffer>(
        t.width, t.height, mode == ReplayMode::Exact ? t.depthFormat : DepthFormat::Unorm24));
    pipelines.push_back(maker->make(*framebuffers.back()));
  }
  // What a pass's draws borrow lives until the pass ends: kept for the whole replay.
  std::vector<std::vector<ClipVertex>> converted;
  for (const Command& c : trace.commands) {
    Pipeline& p = *pipelines[c.target];
    if (const auto* clear = std::get_if<ClearCommand>(&c.what)) {
      p.clear(clear->request);
    } else if (const auto* d = std::get_if<DrawCommand>(&c.what)) {
      DrawCall call;
      call.state = &d->state;
      call.indices = d->indices;
      call.tag = d->tag;
      const FragmentShader* shader = d->shader == kNoShader ? nullptr : &shaders[d->shader];
      if (mode == ReplayMode::Exact) {
        call.vertices = d->vertices;
        call.shader = shader;
      } else {
        call.vertices = converted.emplace_back(fixedFunctionVertices(*d, shader));
        call.shader = shader ? &vertexColours : nullptr;
      }
      p.draw(call);
    } else if (const auto* a = std::get_if<AccumCommand>(&c.what)) {
      p.accumulate(a->state, a->op, a->value);
    } else {
      p.endPass();
    }
  }
  ReplayResult result;
  for (auto& p : pipelines) result.buffers.push_back(buffersOf(p->framebuffer()));
  return result;
}

}  // namespace shadowref::trace
