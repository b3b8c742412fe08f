#include "shadow/shadow_map_renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "gl/accumulation.h"
#include "gl/clear.h"
#include "gl/color_columns.h"
#include "gl/lighting.h"
#include "gl/shader_description.h"
#include "scene/scene_sections.h"
#include "shadow/draw_tag.h"
#include "shadow/light_shadow.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "shadow/soft_lights.h"
#include "shadow/technique.h"
#include "shadow/trapezoid_overlay.h"
#include "shadow/visibility.h"

namespace shadowref {

namespace {

ShadowMapDescription describeLookup(const ShadowLookup& l) {
  return {l.textureMatrix, l.sampler.texture, l.sampler.func, l.sampler.failValue,
          l.pcf,           l.constantBias,      l.outsideLit,   uint8_t(l.receiverPlaneBias)};
}

LightShadowDescription describeLightShadow(const LightShadow& s) {
  LightShadowDescription d;
  d.cube = s.cube;
  if (s.cube) {
    d.lightPosition = s.cubeLookup.lightPosition;
    for (const ShadowLookup& face : s.cubeLookup.faces) d.maps.push_back(describeLookup(face));
  } else {
    d.maps.push_back(describeLookup(s.lookup));
  }
  d.trapezoidal = s.trapezoidal;
  d.lightView = s.views[0].view;
  d.lightProjection = s.views[0].projection;
  return d;
}

// The camera pass's shader: GL_MODULATE of the lit colour by the compare result
// ([Hempe 2004, §5.1.2]), per light: colour = sum over lights of (ambient / n + diffuse_i +
// specular_i) * factor_i. With one light, as in the documents, that is (ambient + light) * (1 or
// the compare-fail value).
class ShadowMappedShader final : public FragmentShader {
 public:
  ShadowMappedShader(const LightingSetup& setup, std::vector<const LightShadow*> shadows)
      : setup_(setup), ambient_(ambientTerm(setup.material, setup.globalAmbient)), eye_(setup.eye), shadows_(std::move(shadows)) {
    for (const PhongLight& light : setup.lights) {
      inRange_.push_back(light.position != glm::dvec4(0.0));
      terms_.push_back(lightTerms(light, setup.material));
    }
  }

  int varyingCount() const override { return 6; }

  bool describe(ShaderDescription& out) const override {
    out = {};
    out.kind = ShaderKind::ShadowMapped;
    out.setup = setup_;
    for (const LightShadow* s : shadows_) out.shadows.push_back(describeLightShadow(*s));
    return true;
  }

  void shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const override {
    if (shadows_.empty()) {
      for (int k = 0; k < batch.count; ++k) out[k] = glm::dvec4(ambient_, 1.0);
      return;
    }
    // shade()'s sum in columns, one channel at a time (the loops vectorise): the same operations
    // per fragment and channel, in the same order.
    double c[3][kMaxBatch], light[3][kMaxBatch];
    double factor[kMaxBatch];
    for (double* channel : c) std::fill_n(channel, batch.count, 0.0);
    const double share = 1.0 / double(shadows_.size());
    const glm::dvec4 plane = receiverPlaneOf(batch.triangle);
    for (size_t i = 0; i < shadows_.size(); ++i) {
      if (inRange_[i]) lightContributions(batch, terms_[i], eye_, light[0], light[1], light[2]);
      else
        for (double* channel : light) std::fill_n(channel, batch.count, 0.0);
      shadows_[i]->factors(batch.varyings[kVaryingPosition], batch.varyings[kVaryingPosition + 1],
                           batch.varyings[kVaryingPosition + 2], batch.count, factor, plane);
      for (int j = 0; j < 3; ++j) {
        const double ambientShare = ambient_[j] * share;
        for (int k = 0; k < batch.count; ++k) c[j][k] += (ambientShare + light[j][k]) * factor[k];
      }
    }
    storeColorColumns(c[0], c[1], c[2], 1.0, batch.count, out);
  }

  glm::dvec4 shade(const FragmentInput& in) const override {
    const double* v = in.varyings;
    const glm::dvec3 p(v[kVaryingPosition], v[kVaryingPosition + 1], v[kVaryingPosition + 2]);
    const glm::dvec3 n = fragmentNormal(in);
    if (shadows_.empty()) return glm::dvec4(ambient_, 1.0);
    glm::dvec3 c(0.0);
    const double share = 1.0 / double(shadows_.size());
    const glm::dvec4 plane = receiverPlaneOf(in.triangle);
    for (size_t i = 0; i < shadows_.size(); ++i) {
      const glm::dvec3 light = inRange_[i] ? lightContribution(terms_[i], p, n, eye_) : glm::dvec3(0.0);
      c += (ambient_ * share + light) * shadows_[i]->factor(p, plane);
    }
    return glm::dvec4(c, 1.0);
  }

 private:
  LightingSetup setup_;  // what it was made from, for describe()
  glm::dvec3 ambient_, eye_;
  std::vector<LightTerms> terms_;
  std::vector<bool> inRange_;  // a light out of range is given as PhongLight{0}: no contribution
  std::vector<const LightShadow*> shadows_;
};

// The camera pass's shader for a Gouraud material: GL_MODULATE as the fixed-function pipeline of
// [Hempe 2004] does it — each light's share of the ambient plus its diffuse and specular, lit per
// vertex (gouraudCameraVertices) and interpolated, times that light's compare result per fragment.
// Varyings: the world position (0..2) for the lookup, then each light's colour.
class ShadowMappedGouraudShader final : public FragmentShader {
 public:
  static constexpr int kFirstColor = 3;
  static constexpr int kMaxLights = (kMaxVaryings - kFirstColor) / 3;

  explicit ShadowMappedGouraudShader(std::vector<const LightShadow*> shadows) : shadows_(std::move(shadows)) {}

  int varyingCount() const override { return kFirstColor + 3 * int(shadows_.size()); }

  bool describe(ShaderDescription& out) const override {
    out = {};
    out.kind = ShaderKind::ShadowMappedGouraud;
    for (const LightShadow* s : shadows_) out.shadows.push_back(describeLightShadow(*s));
    return true;
  }

  // shade()'s sum in columns, one channel at a time over the batch (the loops vectorise): the
  // same operations per fragment, in the same order.
  void shadeBatch(const FragmentBatch& batch, glm::dvec4* out) const override {
    double c[3][kMaxBatch];
    double factor[kMaxBatch];
    for (double* channel : c) std::fill_n(channel, batch.count, 0.0);
    const glm::dvec4 plane = receiverPlaneOf(batch.triangle);
    for (size_t i = 0; i < shadows_.size(); ++i) {
      shadows_[i]->factors(batch.varyings[kVaryingPosition], batch.varyings[kVaryingPosition + 1],
                           batch.varyings[kVaryingPosition + 2], batch.count, factor, plane);
      for (int j = 0; j < 3; ++j) {
        const double* colour = batch.varyings[size_t(kFirstColor) + 3 * i + size_t(j)];
        for (int k = 0; k < batch.count; ++k) c[j][k] += colour[k] * factor[k];
      }
    }
    storeColorColumns(c[0], c[1], c[2], 1.0, batch.count, out);
  }

  glm::dvec4 shade(const FragmentInput& in) const override {
    const double* v = in.varyings;
    const glm::dvec3 p(v[kVaryingPosition], v[kVaryingPosition + 1], v[kVaryingPosition + 2]);
    glm::dvec3 c(0.0);
    const glm::dvec4 plane = receiverPlaneOf(in.triangle);
    for (size_t i = 0; i < shadows_.size(); ++i) {
      const double* colour = v + kFirstColor + 3 * i;
      c += glm::dvec3(colour[0], colour[1], colour[2]) * shadows_[i]->factor(p, plane);
    }
    return glm::dvec4(c, 1.0);
  }

 private:
  std::vector<const LightShadow*> shadows_;
};

// Vertices [first, last) of a Gouraud material for ShadowMappedGouraudShader, made in `lit`: the
// position stays, the normal's varyings and those after it take each light's share of the ambient
// plus the light (shadePoint's terms, in its order: ambient first).
void gouraudCameraVertices(const PreparedInstance& p, const LightingSetup& lighting, double share, ClipVertexBuffer& lit,
                           size_t first, size_t last) {
  const glm::dvec3 ambient = ambientTerm(lighting.material, lighting.globalAmbient) * share;
  for (size_t k = first; k < last; ++k) {
    ClipVertex& v = placeVertex(lit[k], p.vertices[k]);
    const glm::dvec3 pos(v.varyings[kVaryingPosition], v.varyings[kVaryingPosition + 1], v.varyings[kVaryingPosition + 2]);
    const glm::dvec3 n(v.varyings[kVaryingNormal], v.varyings[kVaryingNormal + 1], v.varyings[kVaryingNormal + 2]);
    for (size_t i = 0; i < lighting.lights.size(); ++i) {
      const PhongLight& light = lighting.lights[i];
      glm::dvec3 c = ambient;
      if (light.position != glm::dvec4(0.0)) c += lightContribution(light, lighting.material, pos, n, lighting.eye);
      for (int j = 0; j < 3; ++j) v.varyings[size_t(ShadowMappedGouraudShader::kFirstColor) + 3 * i + size_t(j)] = c[j];
    }
  }
}

// Instances of one material within range of the same lights share a lighting setup and, lit per
// pixel, a shader (as drawLit's groups do, scene_passes.cpp): the outdoor scene's instances have a
// handful of materials. A shader is a function of its setup and the maps: the same bytes.
struct CameraGroup {
  size_t material = 0;
  std::vector<uint8_t> reached;  // per active light: whether it is within range
  LightingSetup lighting;
  std::unique_ptr<FragmentShader> perPixel;  // ShadowMappedShader, made for a per-pixel instance
};

// Step 2 for one set of lights (one accumulation frame): one pass with what was drawn or cleared
// before, which ends here (its shaders and states are its own). Returns false when a Gouraud
// material had to be lit per pixel: more lights than ShadowMappedGouraudShader has varyings for.
bool drawCameraPass(Pipeline& pipeline, const RenderState& state, const Scene& scene, const SceneView& view,
                    std::span<const PreparedInstance> prepared, const std::vector<std::unique_ptr<LightShadow>>& shadows) {
  std::vector<const LightShadow*> active;
  for (const auto& s : shadows) active.push_back(s.get());
  const bool fitGouraud = active.size() <= size_t(ShadowMappedGouraudShader::kMaxLights);
  std::vector<CameraGroup> groups;  // its shaders outlive the pass
  std::vector<size_t> groupOf(prepared.size());
  std::vector<uint8_t> gouraud(prepared.size());
  std::vector<uint8_t> reached(active.size());
  bool gouraudKept = true;
  for (size_t i = 0; i < prepared.size(); ++i) {
    const Instance& inst = *prepared[i].instance;
    const size_t materialIndex = size_t(inst.material);
    const Material& material = scene.materials.at(materialIndex);
    for (size_t l = 0; l < active.size(); ++l) reached[l] = withinRange(active[l]->light, inst.worldBounds);
    size_t g = 0;
    while (g < groups.size() && !(groups[g].material == materialIndex && groups[g].reached == reached)) ++g;
    if (g == groups.size()) {
      CameraGroup& group = groups.emplace_back();
      group.material = materialIndex;
      group.reached = reached;
      group.lighting.material = toPhongMaterial(material);
      group.lighting.globalAmbient = scene.ambient;
      group.lighting.eye = view.eye;
      // A light out of range ([Kuhn 2016, §4.3.1]) contributes nothing but its share of the
      // ambient.
      for (size_t l = 0; l < active.size(); ++l)
        group.lighting.lights.push_back(reached[l] ? toPhongLight(active[l]->light) : PhongLight{glm::dvec4(0.0)});
    }
    groupOf[i] = g;
    const bool wants = material.shading == ShadingModel::Gouraud && !active.empty();
    gouraud[i] = wants && fitGouraud;
    gouraudKept = gouraudKept && (!wants || fitGouraud);
  }
  // The Gouraud materials' vertices lit on all threads, into their instances' shaded vertices
  // (the frame's, refilled for each accumulation frame's pass).
  std::vector<size_t> counts(prepared.size());
  for (size_t i = 0; i < prepared.size(); ++i) {
    if (!gouraud[i]) continue;
    counts[i] = prepared[i].vertices.size();
    prepared[i].shadedVertices.resize(counts[i]);  // constructed by gouraudCameraVertices
  }
  forEachVertexRange(&pipeline, counts, [&](size_t i, size_t first, size_t last) {
    gouraudCameraVertices(prepared[i], groups[groupOf[i]].lighting, 1.0 / double(active.size()),
                          prepared[i].shadedVertices, first, last);
  });
  const ShadowMappedGouraudShader gouraudShader(active);  // outlives the pass too
  const PassStates states(state);
  for (size_t i = 0; i < prepared.size(); ++i) {
    const PreparedInstance& p = prepared[i];
    DrawCall call;
    call.state = &states.of(*p.instance);
    call.vertices = gouraud[i] ? std::span<const ClipVertex>(p.shadedVertices) : std::span<const ClipVertex>(p.vertices);
    call.indices = p.indices;
    call.tag = drawTag(DrawKind::Lit, p.index);
    CameraGroup& group = groups[groupOf[i]];
    if (!gouraud[i] && !group.perPixel) group.perPixel = std::make_unique<ShadowMappedShader>(group.lighting, active);
    call.shader = gouraud[i] ? static_cast<const FragmentShader*>(&gouraudShader) : group.perPixel.get();
    pipeline.draw(call);
  }
  pipeline.endPass();
  return gouraudKept;
}

// The light sets of the accumulation frames: frame k holds the k-th of each light's positions.
// A light without a soft shape is in every frame; its colour is kept, as every frame is a whole
// picture weighted 1/n ([Hempe 2004, §4.2.2]).
std::vector<std::vector<Light>> accumulationFrames(const std::vector<Light>& lights) {
  size_t frames = 1;
  std::vector<std::vector<Light>> expanded;
  for (const Light& l : lights) {
    std::vector<Light> e = expandSoftLight(l);
    for (Light& x : e) x.color = l.color;
    frames = std::max(frames, e.size());
    expanded.push_back(std::move(e));
  }
  std::vector<std::vector<Light>> out(frames);
  for (size_t k = 0; k < frames; ++k)
    for (const std::vector<Light>& e : expanded) out[k].push_back(e[k % e.size()]);
  return out;
}

// --dump shadowmap: each light's map(s) as the camera pass uses them ("L0", "L0.face3"), and for
// TSM the teaching views: "L0" is the warped light view (the scene drawn with N_T as
// projection, [Hempe 2004, Listing 12]), "L0.plain" the same light's unwarped map with the
// trapezoid drawn over it in black (and a cross at the focus point).
void keepShadowMaps(const Scene& scene, const SceneView& view, const std::vector<Instance>& instances,
                    const std::vector<std::unique_ptr<LightShadow>>& shadows, const Pipeline& frame,
                    FrameResult& result) {
  const Camera& camera = scene.camera;
  const std::array<glm::dvec3, 8> frustum =
      frustumCorners(camera, view.aspect, fitFarToBounds(camera, worldBounds(instances)));
  for (size_t i = 0; i < shadows.size(); ++i) {
    const LightShadow& ls = *shadows[i];
    const std::string name = "L" + std::to_string(i);
    for (int f = 0; f < ls.mapCount(); ++f) {
      result.shadowMaps.push_back(ls.textures[size_t(f)]);
      result.shadowMapNames.push_back(name + (ls.cube ? ".face" + std::to_string(f) : ""));
      const LightView& lv = ls.views[size_t(f)];
      // The warped map was drawn with warp · P_light (its x, y and w rows are N_T's).
      result.shadowMapOutlines.push_back({(ls.trapezoidal ? ls.warp : glm::dmat4(1.0)) * lv.projection * lv.view, frustum, {}});
    }
    if (!ls.trapezoidal) continue;
    RasterStats unused;
    DepthTexture plain = renderDepthMap(scene, instances, ls.light, ls.views[0].view, ls.views[0].projection, frame, unused);
    drawTrapezoidOutline(plain, ls.trapezoid);
    result.shadowMaps.push_back(std::move(plain));
    result.shadowMapNames.push_back(name + ".plain");
    result.shadowMapOutlines.push_back({ls.views[0].projection * ls.views[0].view, frustum,
                                        std::vector<glm::dvec2>(std::begin(ls.trapezoid.t), std::end(ls.trapezoid.t))});
  }
}

}  // namespace

std::unique_ptr<FragmentShader> makeShadowMappedShader(const LightingSetup& setup, std::vector<const LightShadow*> shadows) {
  return std::make_unique<ShadowMappedShader>(setup, std::move(shadows));
}

std::unique_ptr<FragmentShader> makeShadowMappedGouraudShader(std::vector<const LightShadow*> shadows) {
  if (shadows.size() > size_t(ShadowMappedGouraudShader::kMaxLights))
    throw std::invalid_argument("a shadow-mapped Gouraud shader takes at most " +
                                std::to_string(ShadowMappedGouraudShader::kMaxLights) + " lights");
  return std::make_unique<ShadowMappedGouraudShader>(std::move(shadows));
}

void renderShadowMaps(const Scene& scene, ShadowMapKind kind, const FrameOptions& options, FrameResult& result,
                      Pipeline& pipeline) {
  const SceneView view = makeCameraView(scene);
  const std::vector<Instance> instances = scene.instances();
  const std::vector<PreparedInstance> prepared = prepareInstances(instances, view, &pipeline);
  const bool trapezoidal = kind == ShadowMapKind::Trapezoidal;

  RenderState state;
  state.viewport = view.viewport;
  state.clipFar = !view.infinite;
  state.cull = CullMode::Back;
  state.depthTest = true;
  state.depthFunc = CompareFunc::Less;

  const std::vector<std::vector<Light>> frames = accumulationFrames(scene.lights);
  const bool accumulating = frames.size() > 1;
  int passCounter = 0;
  // Visibility: each frame's compare results, k² comparisons a light and pixel with k × k PCF.
  std::optional<VisibilityCounts> visibility;
  if (options.keepVisibility) visibility.emplace(scene.lights.size(), pipeline.framebuffer().pixelCount());
  const int pcfHalf = scene.shadow.pcf > 1 ? scene.shadow.pcf / 2 : 0;
  const int comparisons = (2 * pcfHalf + 1) * (2 * pcfHalf + 1);
  for (size_t k = 0; k < frames.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::unique_ptr<LightShadow>> shadows;
    for (const Light& light : frames[k])
      shadows.push_back(buildLightShadow(scene, instances, view, light, trapezoidal, pipeline, result.stats));
    const auto mapsDone = std::chrono::steady_clock::now();
    result.timings.push_back({numberedPass(passCounter, "maps"), std::chrono::duration<double, std::milli>(mapsDone - start).count()});
    if (k == 0 && options.keepShadowMaps) keepShadowMaps(scene, view, instances, shadows, pipeline, result);
    if (k == 0) {
      for (size_t i = 0; i < shadows.size(); ++i) {
        std::ostringstream note;
        note << "light L" << i << " '" << scene.lights[i].name << "': " << (shadows[i]->cube ? "6 cube maps" : "map") << " "
             << scene.shadow.mapSize << "x" << scene.shadow.mapSize;
        if (shadows[i]->trapezoidal)
          note << ", trapezoid " << (shadows[i]->trapezoid.fallback ? "fallback to the bounding rectangle" : "")
               << " eta " << shadows[i]->trapezoid.eta;
        result.notes.push_back(note.str());
      }
    }
    pipeline.clear({.state = state, .color = glm::vec4(glm::vec3(scene.background), 1.0f), .depth = 1.0});
    if (options.onShadowLookups) {
      std::vector<const LightShadow*> looked;
      for (const auto& sh : shadows) looked.push_back(sh.get());
      options.onShadowLookups(looked);
    }
    if (!drawCameraPass(pipeline, state, scene, view, prepared, shadows) && k == 0)
      result.notes.push_back("Gouraud materials lit per pixel: more than " +
                             std::to_string(ShadowMappedGouraudShader::kMaxLights) + " shadow-mapped lights");
    if (visibility) {
      std::vector<const LightShadow*> active;
      for (const auto& sh : shadows) active.push_back(sh.get());
      const std::vector<std::vector<float>> v =
          shadowMapVisibility(pipeline, state, scene.width, scene.height, scene.depthFormat, prepared, active);
      for (size_t l = 0; l < v.size(); ++l) visibility->addFractions(l, v[l], comparisons);
    }
    const std::string name = numberedPass(passCounter, accumulating ? "camera-" + std::to_string(k) : "camera");
    result.timings.push_back({name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mapsDone).count()});
    if (options.onPass) options.onPass(name, pipeline.framebuffer());
    if (accumulating) pipeline.accumulate(state, k == 0 ? AccumOp::Load : AccumOp::Accum, 1.0f / float(frames.size()));
  }
  if (visibility) result.visibility = visibility->finish();
  if (accumulating) {
    pipeline.accumulate(state, AccumOp::Return, 1.0f);
    if (options.onPass) options.onPass(numberedPass(passCounter, "return"), pipeline.framebuffer());
  }
}

// The techniques of this file (technique_registry.cpp lists them).
namespace {

constexpr std::array<TechniqueSetting, 8> kMapSettings = {{
    {"map_size", "8 to 8192"},
    {"offset_factor", "a number"},
    {"offset_units", "a number"},
    {"bias", "a number"},
    {"back_faces_only", "true or false"},
    {"pcf", "1 to 15"},
    {"receiver_plane_bias", "kernel, texel or off"},
    {"compare_fail", "0 to 1"},
}};

// `base` and then `more`: a list that extends another keeps its entries and their order.
template <size_t N>
constexpr std::array<TechniqueSetting, N + 1> extended(const std::array<TechniqueSetting, N>& base,
                                                       TechniqueSetting more) {
  std::array<TechniqueSetting, N + 1> out{};
  std::copy(base.begin(), base.end(), out.begin());
  out[N] = more;
  return out;
}

// The standard map also chooses what its light view is fitted to; TSM keeps its own construction.
constexpr std::array kStandardSettings = extended(kMapSettings, {"fit", "casters or scene"});

// TSM reads the same, and the focus region ([Hempe 2004, §4.1]).
constexpr std::array kTrapezoidalSettings = extended(kMapSettings, {"focus_region", "between 0 and 1 exclusive"});

std::string number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", x);  // %g: the same text on every machine
  return buf;
}

// The receiver-plane bias where it is not the default or does not apply unchanged.
std::string receiverPlaneNote(const ShadowSettings& s) {
  if (s.receiverPlaneBias == ReceiverPlaneBias::Texel) return ", receiver plane at texel centres";
  return s.pcf > 1 && s.receiverPlaneBias == ReceiverPlaneBias::Off ? " without receiver-plane bias" : "";
}

std::string describeMapSettings(const ShadowSettings& s) {
  return "map " + std::to_string(s.mapSize) + " x " + std::to_string(s.mapSize) + ", offset " + number(s.offsetFactor) +
         " / " + number(s.offsetUnits) + ", bias " + number(s.constantBias) +
         (s.backFacesOnly ? ", back faces only" : "") + ", pcf " + std::to_string(s.pcf) +
         receiverPlaneNote(s) + ", compare fail " +
         number(s.compareFail);
}

std::string describeStandardSettings(const ShadowSettings& s) {
  return describeMapSettings(s) + ", fit " + (s.fit == MapFit::Casters ? "casters" : "scene");
}

std::string describeTrapezoidalSettings(const ShadowSettings& s) {
  return describeMapSettings(s) + ", focus region " + number(s.focusRegion);
}

template <ShadowMapKind kind>
void renderMapsOfKind(const Scene& scene, const FrameOptions& options, FrameResult& result, Pipeline& pipeline) {
  renderShadowMaps(scene, kind, options, result, pipeline);
}

}  // namespace

extern const ShadowTechnique kShadowMapTechnique{
    .name = "shadowmap",
    .summary = "shadow maps: a depth map per light, compared per fragment [Williams 1978], [Hempe 2004, §3.1]",
    .settings = kStandardSettings,
    .countsInStencil = false,
    .rendersShadowMaps = true,
    .render = renderMapsOfKind<ShadowMapKind::Standard>,
    .describe = describeStandardSettings,
};

extern const ShadowTechnique kTrapezoidalTechnique{
    .name = "tsm",
    .summary = "trapezoidal shadow maps: the map warped to the view frustum's trapezoid [Martin & Tan 2004], [Hempe 2004, §4.1]",
    .settings = kTrapezoidalSettings,
    .countsInStencil = false,
    .rendersShadowMaps = true,
    .render = renderMapsOfKind<ShadowMapKind::Trapezoidal>,
    .describe = describeTrapezoidalSettings,
};

}  // namespace shadowref
