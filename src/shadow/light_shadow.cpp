#include "shadow/light_shadow.h"

#include <algorithm>
#include <cmath>

#include "raster/clear.h"
#include "raster/renderer.h"
#include "shadow/draw_tag.h"
#include "shadow/focus_body.h"
#include "shadow/focused_trapezoid.h"
#include "shadow/scene_passes.h"

namespace shadowref {

namespace {

void configureLookup(ShadowLookup& lookup, const DepthTexture& texture, const glm::dmat4& T, const ShadowSettings& s) {
  lookup.textureMatrix = T;
  lookup.sampler.texture = &texture;
  lookup.sampler.func = CompareFunc::LEqual;
  lookup.sampler.failValue = s.compareFail;
  lookup.pcf = s.pcf;
  lookup.constantBias = s.constantBias;
}

// 002 §4.1: the trapezoid of the focus body in the light's post-projective space.
void buildTrapezoid(LightShadow& ls, const Scene& scene, const SceneView& view, const Aabb& bounds) {
  const LightView& lv = ls.views[0];
  const glm::dmat4 lightClip = lv.projection * lv.view;
  const Camera& camera = scene.camera;
  // P_inf has no far plane; a far plane beyond the scene only adds empty space.
  const auto corners = frustumCorners(camera, view.aspect, fitFarToBounds(camera, bounds));
  ls.focusBody = focusBody(corners, bounds, lightClip);
  // The body's depth range along the view direction: the ends of the centre line.
  const glm::dvec3 f = glm::normalize(camera.target - camera.eye);
  double dMin = kInfinity, dMax = -kInfinity;
  for (const glm::dvec3& p : ls.focusBody) {
    dMin = std::min(dMin, glm::dot(p - camera.eye, f));
    dMax = std::max(dMax, glm::dot(p - camera.eye, f));
  }
  if (!(dMax > dMin)) dMin = camera.nearPlane, dMax = fitFarToBounds(camera, bounds);
  std::vector<glm::dvec4> bodyClip;
  bodyClip.reserve(ls.focusBody.size());
  for (const glm::dvec3& p : ls.focusBody) bodyClip.push_back(lightClip * glm::dvec4(p, 1.0));
  ls.trapezoid = focusedTrapezoid(transformCorners(lightClip, corners), lightClip * glm::dvec4(camera.eye + f * dMin, 1.0),
                                  lightClip * glm::dvec4(camera.eye + f * dMax, 1.0), bodyClip,
                                  scene.shadow.focusRegion);
  ls.trapezoidal = true;
}

}  // namespace

Aabb sceneBounds(const std::vector<Instance>& instances) {
  Aabb box;
  for (const Instance& inst : instances) {
    if (inst.worldBounds.empty()) continue;
    box.add(inst.worldBounds.min);
    box.add(inst.worldBounds.max);
  }
  return box;
}

DepthTexture renderDepthMap(const Scene& scene, const std::vector<Instance>& instances, const Light& light,
                            const glm::dmat4& view, const glm::dmat4& projection, int threads, RasterStats& stats) {
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

std::unique_ptr<LightShadow> buildLightShadow(const Scene& scene, const std::vector<Instance>& instances,
                                              const SceneView& view, const Light& light, bool trapezoidal,
                                              int threads, RasterStats& stats) {
  auto ls = std::make_unique<LightShadow>();
  ls->light = light;
  const Aabb bounds = sceneBounds(instances);
  if (light.type == LightType::Point) {
    // Beyond the documents: six perspective maps, one per cube face.
    ls->cube = true;
    ls->cubeLookup.lightPosition = light.position;
    ls->views = pointLightCubeViews(light, bounds);
    for (size_t f = 0; f < 6; ++f) {
      ls->textures[f] = renderDepthMap(scene, instances, light, ls->views[f].view, ls->views[f].projection, threads, stats);
      configureLookup(ls->cubeLookup.faces[f], ls->textures[f], textureMatrix(ls->views[f]), scene.shadow);
    }
    return ls;
  }
  ls->views[0] = shadowLightView(light, bounds);
  const LightView& lv = ls->views[0];
  glm::dmat4 projection = lv.projection;
  glm::dmat4 T = textureMatrix(lv);
  if (trapezoidal) {
    // 002 Listings 11, 12: the map drawn with N_T · P_light, looked up with bias · N_T · P_light ·
    // V_light. Inside the trapezoid the warped w is ≥ 1 (trapezoid.h), so the light's depths stay
    // within [−1, 1] and nothing of the map's content meets the near or far plane.
    buildTrapezoid(*ls, scene, view, bounds);
    projection = ls->trapezoid.NT * lv.projection;
    T = textureMatrix(lv, ls->trapezoid.NT);
  }
  ls->textures[0] = renderDepthMap(scene, instances, light, lv.view, projection, threads, stats);
  configureLookup(ls->lookup, ls->textures[0], T, scene.shadow);
  return ls;
}

}  // namespace shadowref
