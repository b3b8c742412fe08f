#include "shadow/shadow_map_renderer.h"

#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>

#include "raster/accumulation.h"
#include "raster/clear.h"
#include "raster/lighting.h"
#include "shadow/draw_tag.h"
#include "shadow/light_view.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_lookup.h"
#include "shadow/soft_lights.h"
#include "shadow/trapezoid.h"

namespace shadowref {

namespace {

Aabb sceneBounds(const std::vector<Instance>& instances) {
  Aabb box;
  for (const Instance& inst : instances) {
    if (inst.worldBounds.empty()) continue;
    box.add(inst.worldBounds.min);
    box.add(inst.worldBounds.max);
  }
  return box;
}

// One light's maps and how the camera pass looks them up.
struct LightShadow {
  Light light;
  bool cube = false;
  std::array<DepthTexture, 6> textures;  // [0] only, unless cube
  ShadowLookup lookup;
  CubeShadowLookup cubeLookup;
  bool trapezoidal = false;
  Trapezoid trapezoid;

  double factor(const glm::dvec3& p) const { return cube ? cubeLookup.factor(p) : lookup.factor(p); }
};

// Step 1: depth from the light into a size x size map. `projection` is P_light, or N_T · P_light
// for TSM (002 Listing 11). Casters are the instances' shadow meshes (the low-poly proxy where
// given, 004) within the light's range.
DepthTexture renderDepthMap(const Scene& scene, const std::vector<Instance>& instances, const Light& light,
                            const glm::dmat4& view, const glm::dmat4& projection, bool warped, int threads,
                            RasterStats& stats) {
  const int size = scene.shadow.mapSize;
  Framebuffer fb(size, size, scene.depthFormat);
  Renderer renderer(fb, threads);
  RenderState state;
  state.viewport = Viewport{0, 0, size, size, 0.0, 1.0};
  state.depthTest = true;
  state.depthFunc = CompareFunc::Less;
  state.colorMask = {false, false, false, false};
  // 002 §3.2: either polygon offset or only the back faces in the map.
  state.cull = scene.shadow.backFacesOnly ? CullMode::Front : CullMode::None;
  state.polygonOffset = {scene.shadow.offsetFactor != 0.0 || scene.shadow.offsetUnits != 0.0,
                         scene.shadow.offsetFactor, scene.shadow.offsetUnits};
  // N_T rescales z by its w per texel; without near/far clipping nothing of the focus region is
  // lost to the rescaled planes, and the lookup clamps r to [0, 1] exactly as the map clamps depth.
  state.depthClamp = warped;
  clearDepth(fb, state, 1.0);

  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;
  for (size_t i = 0; i < instances.size(); ++i) {
    const Instance& inst = instances[i];
    if (!inst.shadowMesh || !withinRange(light, inst.shadowBounds)) continue;
    const VertexTransform xf{view * inst.world, projection};
    const Mesh& mesh = *inst.shadowMesh;
    vertices.resize(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) vertices[v].position = xf.toClip(glm::dvec4(mesh.positions[v], 1.0));
    indices.clear();
    for (const glm::uvec3& t : mesh.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
    RenderState mirrored;
    DrawCall call;
    call.state = &stateFor(state, inst, mirrored);
    call.vertices = vertices;
    call.indices = indices;
    call.tag = drawTag(DrawKind::ShadowMap, int(i));
    renderer.draw(call);
  }
  stats += renderer.stats();
  DepthTexture tex;
  tex.width = tex.height = size;
  tex.depth.resize(fb.depthCodes().size());
  for (size_t i = 0; i < tex.depth.size(); ++i) tex.depth[i] = float(fb.depthCodec().decode(fb.depthCodes()[i]));
  return tex;
}

// N_T carries z unchanged (z row (0, 0, 1, 0)) and divides it by its w' per texel, which keeps
// depth exactly affine across each triangle in the warped map, but where w' < 1 pushes z/w' out of
// [-1, 1]: those depths would clamp to the far plane and lose every shadow there. Scaling the z
// row by k = the smallest w' at the trapezoid's corners (w' is affine, so that is its minimum over
// the map) keeps |k z / w'| <= 1; the camera pass looks up with the same matrix, so the comparison
// is unchanged, and only depth resolution varies across the map (by max w' / min w').
glm::dmat4 depthPreservingWarp(const Trapezoid& trapezoid) {
  glm::dmat4 warp = trapezoid.NT;
  double k = kInfinity;
  for (const glm::dvec2& t : trapezoid.t) k = std::min(k, (warp * glm::dvec4(t, 0.0, 1.0)).w);
  if (k > 0.0 && k < 1.0) warp[2][2] *= k;
  return warp;
}

void configureLookup(ShadowLookup& lookup, const DepthTexture& texture, const glm::dmat4& T, const ShadowSettings& s) {
  lookup.textureMatrix = T;
  lookup.sampler.texture = &texture;
  lookup.sampler.func = CompareFunc::LEqual;
  lookup.sampler.failValue = s.compareFail;
  lookup.pcf = s.pcf;
  lookup.constantBias = s.constantBias;
}

std::unique_ptr<LightShadow> buildLightShadow(const Scene& scene, const std::vector<Instance>& instances,
                                              const Aabb& bounds, const SceneView& view, const Light& light,
                                              bool trapezoidal, int threads, FrameResult& result) {
  auto ls = std::make_unique<LightShadow>();
  ls->light = light;
  if (light.type == LightType::Point) {
    // Beyond the documents: six perspective maps, one per cube face.
    ls->cube = true;
    ls->cubeLookup.lightPosition = light.position;
    const std::array<LightView, 6> views = pointLightCubeViews(light, bounds);
    for (int f = 0; f < 6; ++f) {
      ls->textures[size_t(f)] = renderDepthMap(scene, instances, light, views[size_t(f)].view, views[size_t(f)].projection,
                                               false, threads, result.stats);
      configureLookup(ls->cubeLookup.faces[size_t(f)], ls->textures[size_t(f)], textureMatrix(views[size_t(f)]), scene.shadow);
    }
    return ls;
  }
  const LightView lv = light.type == LightType::Directional ? directionalLightView(light, bounds)
                                                           : spotLightView(light, bounds);
  glm::dmat4 projection = lv.projection;
  glm::dmat4 T = textureMatrix(lv);
  if (trapezoidal) {
    // 002 §4.1: the camera frustum in the light's post-projective space, its trapezoid, N_T.
    const double far = std::isinf(scene.camera.farPlane) ? fitFarToBounds(scene.camera, bounds) : scene.camera.farPlane;
    const auto corners = transformCorners(lv.projection * lv.view, frustumCorners(scene.camera, view.aspect, far));
    ls->trapezoid = computeTrapezoid(corners, scene.shadow.focusRegion);
    ls->trapezoidal = true;
    const glm::dmat4 warp = depthPreservingWarp(ls->trapezoid);
    projection = warp * lv.projection;
    T = textureMatrix(lv, warp);
  }
  ls->textures[0] = renderDepthMap(scene, instances, light, lv.view, projection, trapezoidal, threads, result.stats);
  configureLookup(ls->lookup, ls->textures[0], T, scene.shadow);
  return ls;
}

// The camera pass's shader: 002's GL_MODULATE of the lit colour by the compare result, per light:
// colour = sum over lights of (ambient / n + diffuse_i + specular_i) * factor_i. With one light,
// as in the documents, that is (ambient + light) * (1 or the compare-fail value).
class ShadowMappedShader final : public PerPixelLightingShader {
 public:
  ShadowMappedShader(const LightingSetup& setup, const std::vector<const LightShadow*>& shadows)
      : PerPixelLightingShader(setup), shadows_(shadows) {}

  glm::dvec4 shade(const FragmentInput& in) const override {
    const double* v = in.varyings;
    const glm::dvec3 p(v[kVaryingPosition], v[kVaryingPosition + 1], v[kVaryingPosition + 2]);
    glm::dvec3 n(v[kVaryingNormal], v[kVaryingNormal + 1], v[kVaryingNormal + 2]);
    const double len = glm::length(n);
    if (len > 0.0) n /= len;
    if (in.facing == BackFacing) n = -n;
    const glm::dvec3 ambient = ambientTerm(setup_.material, setup_.globalAmbient);
    if (shadows_.empty()) return glm::dvec4(ambient, 1.0);
    glm::dvec3 c(0.0);
    const double share = 1.0 / double(shadows_.size());
    for (size_t i = 0; i < shadows_.size(); ++i) {
      const glm::dvec3 light = setup_.lights[i].position == glm::dvec4(0.0)
                                   ? glm::dvec3(0.0)
                                   : lightContribution(setup_.lights[i], setup_.material, p, n, setup_.eye);
      c += (ambient * share + light) * shadows_[i]->factor(p);
    }
    return glm::dvec4(c, 1.0);
  }

 private:
  const std::vector<const LightShadow*>& shadows_;
};

// Step 2 for one set of lights (one accumulation frame).
void drawCameraPass(Renderer& renderer, const RenderState& state, const Scene& scene, const SceneView& view,
                    const std::vector<PreparedInstance>& prepared, const std::vector<std::unique_ptr<LightShadow>>& shadows) {
  for (const PreparedInstance& p : prepared) {
    const Material& material = scene.materials.at(size_t(p.instance->material));
    LightingSetup lighting;
    lighting.material = toPhongMaterial(material);
    lighting.globalAmbient = scene.ambient;
    lighting.eye = view.eye;
    std::vector<const LightShadow*> active;
    for (const auto& s : shadows) {
      active.push_back(s.get());
      // A light out of range (000 §4.3.1) contributes nothing but its share of the ambient.
      lighting.lights.push_back(withinRange(s->light, p.instance->worldBounds) ? toPhongLight(s->light) : PhongLight{glm::dvec4(0.0)});
    }
    const ShadowMappedShader shader(lighting, active);
    RenderState mirrored;
    DrawCall call;
    call.state = &stateFor(state, *p.instance, mirrored);
    call.vertices = p.vertices;
    call.indices = p.indices;
    call.shader = &shader;
    call.tag = drawTag(DrawKind::Lit, p.index);
    renderer.draw(call);
  }
}

// The light sets of the accumulation frames: frame k holds the k-th of each light's positions.
// A light without a soft shape is in every frame; its colour is kept, as every frame is a whole
// picture weighted 1/n (002 §4.2.2).
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

std::string passName(int& counter, const std::string& what) {
  char number[16];
  std::snprintf(number, sizeof number, "%02d-", ++counter);
  return number + what;
}

}  // namespace

void renderShadowMaps(const Scene& scene, ShadowMethod method, const FrameOptions& options, FrameResult& result,
                      Renderer& renderer) {
  const SceneView view = makeCameraView(scene);
  const std::vector<Instance> instances = scene.instances();
  const std::vector<PreparedInstance> prepared = prepareInstances(instances, view);
  const Aabb bounds = sceneBounds(instances);
  Framebuffer& fb = renderer.framebuffer();
  const bool trapezoidal = method == ShadowMethod::Trapezoidal;

  RenderState state;
  state.viewport = view.viewport;
  state.clipFar = !view.infinite;
  state.cull = CullMode::Back;
  state.depthTest = true;
  state.depthFunc = CompareFunc::Less;

  const std::vector<std::vector<Light>> frames = accumulationFrames(scene.lights);
  const bool accumulating = frames.size() > 1;
  int passCounter = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    std::vector<std::unique_ptr<LightShadow>> shadows;
    for (const Light& light : frames[k])
      shadows.push_back(buildLightShadow(scene, instances, bounds, view, light, trapezoidal, renderer.threads(), result));
    const auto mapsDone = std::chrono::steady_clock::now();
    result.timings.push_back({passName(passCounter, "maps"), std::chrono::duration<double, std::milli>(mapsDone - start).count()});
    if (k == 0 && options.keepShadowMaps) {
      for (size_t i = 0; i < shadows.size(); ++i)
        for (int f = 0; f < (shadows[i]->cube ? 6 : 1); ++f) {
          result.shadowMaps.push_back(shadows[i]->textures[size_t(f)]);
          result.shadowMapNames.push_back("L" + std::to_string(i) + (shadows[i]->cube ? ".face" + std::to_string(f) : ""));
        }
    }
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
    clearColor(fb, state, glm::vec4(glm::vec3(scene.background), 1.0f));
    clearDepth(fb, state, 1.0);
    drawCameraPass(renderer, state, scene, view, prepared, shadows);
    const std::string name = passName(passCounter, accumulating ? "camera-" + std::to_string(k) : "camera");
    result.timings.push_back({name, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mapsDone).count()});
    if (options.onPass) options.onPass(name, fb);
    if (accumulating) accumulate(fb, state, k == 0 ? AccumOp::Load : AccumOp::Accum, 1.0f / float(frames.size()));
  }
  if (accumulating) {
    accumulate(fb, state, AccumOp::Return, 1.0f);
    if (options.onPass) options.onPass(passName(passCounter, "return"), fb);
  }
}

}  // namespace shadowref
