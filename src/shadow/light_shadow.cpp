#include "shadow/light_shadow.h"

#include <algorithm>
#include <bit>
#include <cmath>

#include "gl/clear.h"
#include "gl/lighting.h"
#include "shadow/caster_fit.h"
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
  lookup.receiverPlaneBias = s.receiverPlaneBias;
}

// [Hempe 2004, §4.1]: the trapezoid of the focus body in the light's post-projective space.
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
  ls.depthAnchor = camera.eye + f * dMin;
}

// The half-space in front of the light's near plane, −z_eye ≥ near, in object coordinates of a
// mesh drawn with `modelView` (V_light · world).
HalfSpace frontOf(const glm::dmat4& modelView, double near) {
  const glm::dvec4 row2(modelView[0][2], modelView[1][2], modelView[2][2], modelView[3][2]);
  return HalfSpace{-glm::dvec3(row2), -row2.w - near};
}

// A perspective light's map warped by N_T needs its triangles clipped to the front of the light
// BEFORE the warp: N_T mixes w into x, y and w, so a point behind the light (w < 0) can come out
// with w' > 0 inside the square, and the rasterizer's clipping, done after the warp, would keep
// it (geometry behind the light would draw over the map). Triangles wholly in front keep their
// vertices; the others are clipped (Sutherland–Hodgman) and fanned from new vertices.
void appendClippedTriangles(const Mesh& mesh, const HalfSpace& front, const VertexTransform& xf,
                            std::vector<ClipVertex>& vertices, std::vector<uint32_t>& indices) {
  for (const glm::uvec3& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    if (front.signedDistance(a) >= 0.0 && front.signedDistance(b) >= 0.0 && front.signedDistance(c) >= 0.0) {
      indices.insert(indices.end(), {t.x, t.y, t.z});
      continue;
    }
    const ConvexPolygon clipped = clipPolygon({a, b, c}, front);
    if (clipped.size() < 3) continue;
    const uint32_t first = uint32_t(vertices.size());
    for (const glm::dvec3& p : clipped) {
      ClipVertex v;
      v.position = xf.toClip(glm::dvec4(p, 1.0));
      vertices.push_back(v);
    }
    for (uint32_t k = 1; k + 1 < clipped.size(); ++k) indices.insert(indices.end(), {first, first + k, first + k + 1});
  }
}

}  // namespace

double pcfOffsetFactor(double offsetFactor, int pcf, ReceiverPlaneBias receiverPlaneBias) {
  return receiverPlaneBias != ReceiverPlaneBias::Off ? offsetFactor : offsetFactor * double(pcfKernelWidth(pcf));
}

glm::dmat4 focusedDepthWarp(const glm::dmat4& NT, const LightView& light, const std::vector<glm::dvec3>& body,
                            const glm::dvec3& anchor) {
  const glm::dmat4 lightClip = light.projection * light.view;
  double zMin = kInfinity, zMax = -kInfinity;
  for (const glm::dvec3& p : body) {
    const glm::dvec4 c = lightClip * glm::dvec4(p, 1.0);
    if (!(c.w > 0.0)) continue;
    zMin = std::min(zMin, c.z / c.w);
    zMax = std::max(zMax, c.z / c.w);
  }
  if (!(zMax >= zMin)) zMin = -1.0, zMax = 1.0;
  const glm::dvec4 a = lightClip * glm::dvec4(anchor, 1.0);
  const double centre = a.w > 0.0 ? std::clamp(a.z / a.w, zMin, zMax) : 0.5 * (zMin + zMax);
  const double half = std::max(std::max(zMax - centre, centre - zMin) * (1.0 + kFocusedDepthMargin), kMinFocusedDepthHalfRange);
  const double scale = 1.0 / half;
  // z' = scale · (z − centre · w) in the light's clip coordinates (x, y, z, w): divided by the
  // warped w' = w'' · w it gives scale · (Z − centre) / w''. Row 2 = scale · (e_z − centre · e_w).
  glm::dmat4 warp = NT;
  warp[0][2] = 0.0;
  warp[1][2] = 0.0;
  warp[2][2] = scale;
  warp[3][2] = -scale * centre;
  return warp;
}

glm::dvec4 receiverPlaneOf(const ClipVertex* const triangle[3]) {
  if (!triangle[0] || !triangle[1] || !triangle[2]) return glm::dvec4(0.0);
  auto position = [&](int i) {
    const double* v = triangle[i]->varyings.data() + kVaryingPosition;
    return glm::dvec3(v[0], v[1], v[2]);
  };
  return trianglePlane(position(0), position(1), position(2));
}

double LightShadow::factor(const glm::dvec3& p, const glm::dvec4& receiverPlane) const {
  if (cube) return cubeLookup.factor(p, receiverPlane);
  if (trapezoidal && !((views[0].projection * (views[0].view * glm::dvec4(p, 1.0))).w > 0.0)) return 1.0;
  return lookup.factor(p, receiverPlane);
}

void LightShadow::factors(const double* x, const double* y, const double* z, int count, double* out,
                          const glm::dvec4& receiverPlane) const {
  if (cube) {
    for (int k = 0; k < count; ++k) out[k] = cubeLookup.factor({x[k], y[k], z[k]}, receiverPlane);
    return;
  }
  lookup.factors(x, y, z, count, out, receiverPlane);
  if (!trapezoidal) return;
  for (int k = 0; k < count; ++k)
    if (!((views[0].projection * (views[0].view * glm::dvec4(x[k], y[k], z[k], 1.0))).w > 0.0)) out[k] = 1.0;
}

DepthTexture renderDepthMap(const Scene& scene, const std::vector<Instance>& instances, const Light& light,
                            const glm::dmat4& view, const glm::dmat4& projection, const Pipeline& frame,
                            RasterStats& stats, double clipNear, bool depthClamp) {
  const int size = scene.shadow.mapSize;
  Framebuffer fb(size, size, scene.depthFormat);
  const std::unique_ptr<Pipeline> pipeline = frame.forFramebuffer(fb);
  RenderState state;
  state.viewport = Viewport{0, 0, size, size, 0.0, 1.0};
  state.depthTest = true;
  state.depthFunc = CompareFunc::Less;
  state.colorMask = {false, false, false, false};
  // [Hempe 2004, §3.2]: either polygon offset or only the back faces in the map.
  state.cull = scene.shadow.backFacesOnly ? CullMode::Front : CullMode::None;
  state.polygonOffset = {scene.shadow.offsetFactor != 0.0 || scene.shadow.offsetUnits != 0.0,
                         pcfOffsetFactor(scene.shadow.offsetFactor, scene.shadow.pcf, scene.shadow.receiverPlaneBias),
                         scene.shadow.offsetUnits};
  // A focused depth range (focusedDepthWarp) puts casters between the light and the focus body
  // before the near plane: clamped to depth 0 they still shadow everything behind them.
  state.depthClamp = depthClamp;
  pipeline->clear({.state = state, .depth = 1.0});  // one pass with the draws below

  // Every caster's vertices in the light's clip space, on all threads, and its indices where the
  // near plane clips (unclipped, a caster draws its mesh's own indices): the pass's, alive until
  // it ends below.
  std::vector<size_t> casters;
  for (size_t i = 0; i < instances.size(); ++i)
    if (instances[i].shadowMesh && withinRange(light, instances[i].shadowBounds)) casters.push_back(i);
  std::vector<std::vector<ClipVertex>> vertices(casters.size());
  std::vector<std::vector<uint32_t>> clippedIndices(clipNear > 0.0 ? casters.size() : 0);
  std::vector<std::span<const uint32_t>> indices(casters.size());
  pipeline->forEachIndependent(int(casters.size()), [&](int c) {
    const Instance& inst = instances[casters[size_t(c)]];
    const VertexTransform xf{view * inst.world, projection};
    const Mesh& mesh = *inst.shadowMesh;
    std::vector<ClipVertex>& v = vertices[size_t(c)];
    v.resize(mesh.positions.size());
    for (size_t k = 0; k < mesh.positions.size(); ++k) v[k].position = xf.toClip(glm::dvec4(mesh.positions[k], 1.0));
    if (clipNear > 0.0) {
      std::vector<uint32_t>& clipped = clippedIndices[size_t(c)];
      appendClippedTriangles(mesh, frontOf(xf.modelView, clipNear), xf, v, clipped);
      indices[size_t(c)] = clipped;
    } else {
      indices[size_t(c)] = triangleIndices(mesh);
    }
  });
  const PassStates states(state);
  for (size_t c = 0; c < casters.size(); ++c) {
    DrawCall call;
    call.state = &states.of(instances[casters[c]]);
    call.vertices = vertices[c];
    call.indices = indices[c];
    call.tag = drawTag(DrawKind::ShadowMap, int(casters[c]));
    pipeline->draw(call);
  }
  pipeline->endPass();
  stats += pipeline->stats();
  DepthTexture tex;
  tex.width = tex.height = size;
  // Float32 codes are the floats' bits already (decode, then float(), gives them back unchanged):
  // the buffer becomes the texture. Unorm24 codes are converted in place.
  tex.bits = std::move(pipeline->framebuffer().depthCodes());
  if (fb.depthCodec().format != DepthFormat::Float32)
    for (uint32_t& texel : tex.bits) texel = std::bit_cast<uint32_t>(float(fb.depthCodec().decode(texel)));
  return tex;
}

StandardMapView standardMapView(const Scene& scene, const std::vector<Instance>& instances, const SceneView& view,
                                const Light& light, const Aabb& bounds) {
  if (light.type != LightType::Directional || scene.shadow.fit != MapFit::Casters)
    return {shadowLightView(light, bounds), false, {}};
  const Camera& camera = scene.camera;
  CasterFit fit = fitDirectionalToCasters(light, instances, bounds,
                                          frustumCorners(camera, view.aspect, fitFarToBounds(camera, bounds)),
                                          camera.eye, scene.shadow.mapSize, scene.shadow.pcf);
  return {fit.view, fit.fitted, std::move(fit.casters)};
}

std::unique_ptr<LightShadow> buildLightShadow(const Scene& scene, const std::vector<Instance>& instances,
                                              const SceneView& view, const Light& light, bool trapezoidal,
                                              const Pipeline& frame, RasterStats& stats) {
  auto ls = std::make_unique<LightShadow>();
  ls->light = light;
  const Aabb bounds = worldBounds(instances);
  if (light.type == LightType::Point) {
    // Beyond the documents: six perspective maps, one per cube face.
    ls->cube = true;
    ls->cubeLookup.lightPosition = light.position;
    ls->views = pointLightCubeViews(light, bounds);
    for (size_t f = 0; f < 6; ++f) {
      ls->textures[f] = renderDepthMap(scene, instances, light, ls->views[f].view, ls->views[f].projection, frame, stats);
      configureLookup(ls->cubeLookup.faces[f], ls->textures[f], textureMatrix(ls->views[f]), scene.shadow);
    }
    return ls;
  }
  if (trapezoidal) {
    // TSM keeps the scene box's light view: its trapezoid focuses the map itself.
    ls->views[0] = shadowLightView(light, bounds);
  } else {
    StandardMapView standard = standardMapView(scene, instances, view, light, bounds);
    ls->views[0] = standard.view;
    ls->fittedToCasters = standard.fittedToCasters;
    ls->fittedCasters = std::move(standard.casters);
  }
  const LightView& lv = ls->views[0];
  glm::dmat4 projection = lv.projection;
  glm::dmat4 T = textureMatrix(lv);
  if (trapezoidal) {
    // [Hempe 2004, Listings 11, 12]: the map drawn with N_T · P_light, looked up with bias · N_T ·
    // P_light · V_light. Inside the trapezoid the warped w is ≥ 1 (trapezoid.h), so the light's
    // depths stay within [−1, 1] and nothing of the map's content meets the near or far plane.
    buildTrapezoid(*ls, scene, view, bounds);
    // An affine N_T (the bounding-rectangle fallback, parallel side lines) has w'' = 1: no false
    // gradient to remove, and the map is a standard map of the rectangle.
    const glm::dmat4& NT = ls->trapezoid.NT;
    ls->focusedDepth = !(NT[0][3] == 0.0 && NT[1][3] == 0.0 && NT[2][3] == 0.0 && NT[3][3] == 1.0);
    ls->warp = ls->focusedDepth ? focusedDepthWarp(NT, lv, ls->focusBody, ls->depthAnchor) : NT;
    projection = ls->warp * lv.projection;
    T = textureMatrix(lv, ls->warp);
  }
  const bool clipToFront = trapezoidal && light.type == LightType::Spot;
  ls->textures[0] = renderDepthMap(scene, instances, light, lv.view, projection, frame, stats,
                                   clipToFront ? lv.nearPlane : 0.0, ls->focusedDepth);
  configureLookup(ls->lookup, ls->textures[0], T, scene.shadow);
  ls->lookup.outsideLit = ls->fittedToCasters;
  return ls;
}

}  // namespace shadowref
