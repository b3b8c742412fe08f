#include "shadow/volume_renderer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <numeric>
#include <optional>

#include "gl/clear.h"
#include "gl/fragment_shader.h"
#include "scene/scene_sections.h"
#include "shadow/draw_tag.h"
#include "shadow/facing.h"
#include "shadow/occlusion_pyramid.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_volume.h"
#include "shadow/soft_lights.h"
#include "shadow/stencil_counting.h"
#include "shadow/technique.h"
#include "shadow/visibility.h"
#include "shadow/volume_casting.h"

namespace shadowref {

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The counting an object gets: fixed by the method, or McGuire's choice for `auto`
// ([Kuhn 2016, §4.2.1, §4.3.2]): z-fail only where the object's box reaches into the occlusion
// pyramid between the light and the near plane, where z-pass could miscount.
StencilCounting countingFor(VolumeCounting method, const Instance& inst, const Scene& scene, const SceneView& view,
                            const Light& light) {
  if (method == VolumeCounting::ZPass) return StencilCounting::ZPass;
  if (method == VolumeCounting::ZFail) return StencilCounting::ZFail;
  return needsZFail(inst.shadowBounds, scene.camera, view.aspect, light.homogeneous()) ? StencilCounting::ZFail
                                                                                      : StencilCounting::ZPass;
}

struct LightTotals {
  size_t objects = 0, zpass = 0, zfail = 0;
  std::vector<std::string> zfailObjects;  // which objects auto sent to z-fail
  ShadowVolumeStats volume;
};

// One instance's volume for one light, transformed to clip space with the instance's own
// VertexTransform: the front cap's vertices are the scene pass's vertices, bit for bit. Cache
// lines of its own: the casters' volumes are built side by side on all threads.
struct alignas(128) VolumeDraw {
  ShadowVolume volume;
  ShadowVolumeWorkspace workspace;
  std::vector<ClipVertex> vertices;
  std::array<std::vector<uint32_t>, 3> indices;  // per VolumePart; the draws borrow them until their pass ends
  bool mirrored = false;  // the instance built has a world matrix that mirrors

  void build(const PreparedInstance& p, const Light& light, const ShadowSettings& settings, bool withCaps) {
    const glm::dvec4 objectLight = lightInObjectSpace(p.instance->world, light.homogeneous());
    buildShadowVolume(*p.instance->shadowMesh, objectLight, settings.silhouette, withCaps, volume, &workspace);
    mirrored = p.instance->mirrored;
    vertices.resize(volume.positions.size());
    for (size_t i = 0; i < volume.positions.size(); ++i) vertices[i].position = p.transform.toClip(volume.positions[i]);
    for (const VolumePart part : {VolumePart::Side, VolumePart::FrontCap, VolumePart::BackCap}) {
      std::vector<uint32_t>& list = indices[size_t(part)];
      list.clear();
      for (const glm::uvec3& t : volume.part(part)) list.insert(list.end(), {t.x, t.y, t.z});
    }
  }

  void draw(Pipeline& pipeline, const PassStates& states, VolumePart part, DrawKind kind, int instance,
            const FragmentShader* shader) const {
    const std::vector<uint32_t>& list = indices[size_t(part)];
    if (list.empty()) return;
    DrawCall call;
    call.state = mirrored ? &states.mirrored : &states.plain;
    call.vertices = vertices;
    call.indices = list;
    call.shader = shader;
    call.tag = drawTag(kind, instance);
    pipeline.draw(call);
  }

  void drawAll(Pipeline& pipeline, const PassStates& states, int instance, const FragmentShader* shader = nullptr) const {
    draw(pipeline, states, VolumePart::Side, DrawKind::VolumeSides, instance, shader);
    draw(pipeline, states, VolumePart::FrontCap, DrawKind::FrontCap, instance, shader);
    draw(pipeline, states, VolumePart::BackCap, DrawKind::BackCap, instance, shader);
  }
};

// The states of a pass with their mirrored copies (PassStates), alive as long as the pass.
std::vector<PassStates> withMirrored(const std::vector<RenderState>& states) {
  return std::vector<PassStates>(states.begin(), states.end());
}

bool castsFor(const PreparedInstance& p, const Light& light) {
  return p.instance->shadowMesh != nullptr && withinRange(light, p.instance->shadowBounds);
}

// Step 2: the volumes of every caster into the (cleared) stencil buffer. The volumes are built
// first, on all threads (each caster's own, independent of the others), then drawn in the
// casters' order, one pass that ends here; `volumes` (the frame's) keeps their arrays.
LightTotals drawVolumePass(Pipeline& pipeline, const RenderState& base, const Scene& scene, const SceneView& view,
                           std::span<const PreparedInstance> prepared, const Light& light, VolumeCounting method,
                           std::vector<VolumeDraw>& volumes) {
  LightTotals totals;
  const CountingOptions counting{scene.shadow.twoSidedStencil, scene.shadow.wrapOps};
  std::vector<const PreparedInstance*> casters;
  std::vector<StencilCounting> how;
  casters.reserve(prepared.size());
  how.reserve(prepared.size());
  for (const PreparedInstance& p : prepared) {
    if (!castsFor(p, light)) continue;
    casters.push_back(&p);
    how.push_back(countingFor(method, *p.instance, scene, view, light));
  }
  if (volumes.size() < casters.size()) volumes.resize(casters.size());
  // The largest casters' volumes first: the threads take the builds one at a time, and one that
  // starts a large build last keeps the other waiting.
  std::vector<size_t> largestFirst(casters.size());
  std::iota(largestFirst.begin(), largestFirst.end(), size_t(0));
  std::stable_sort(largestFirst.begin(), largestFirst.end(), [&](size_t a, size_t b) {
    return casters[a]->instance->shadowMesh->triangles.size() > casters[b]->instance->shadowMesh->triangles.size();
  });
  pipeline.forEachIndependent(int(casters.size()), [&](int k) {
    const size_t i = largestFirst[size_t(k)];
    volumes[i].build(*casters[i], light, scene.shadow, how[i] == StencilCounting::ZFail);
  });
  // The counting states of each kind, made once for the pass rather than once a caster.
  const std::vector<PassStates> zpassStates = withMirrored(volumePassStates(base, StencilCounting::ZPass, counting));
  const std::vector<PassStates> zfailStates = withMirrored(volumePassStates(base, StencilCounting::ZFail, counting));
  for (size_t i = 0; i < casters.size(); ++i) {
    const PreparedInstance& p = *casters[i];
    VolumeDraw& volume = volumes[i];
    ++totals.objects;
    ++(how[i] == StencilCounting::ZFail ? totals.zfail : totals.zpass);
    if (how[i] == StencilCounting::ZFail && method == VolumeCounting::PerCaster) totals.zfailObjects.push_back(p.instance->path);
    totals.volume.silhouetteEdges += volume.volume.stats.silhouetteEdges;
    totals.volume.sideTriangles += volume.volume.stats.sideTriangles;
    totals.volume.frontCapTriangles += volume.volume.stats.frontCapTriangles;
    totals.volume.backCapTriangles += volume.volume.stats.backCapTriangles;
    for (const PassStates& states : how[i] == StencilCounting::ZFail ? zfailStates : zpassStates)
      volume.drawAll(pipeline, states, p.index);
  }
  pipeline.endPass();
  return totals;
}

// Teaching views: front faces red / back faces blue ([SV slides]), or each scene light's own pair
// of colours (FrameOptions::volumeColours); or translucent red volumes ([DSS article]). One pass
// a light: its casters' volumes built into `volumes` (the frame's), then drawn in the casters'
// order. owner[i]: the scene light lights[i] came from.
void drawVolumeView(Pipeline& pipeline, const RenderState& base, const Scene& scene, const SceneView& view,
                    std::span<const PreparedInstance> prepared, const std::vector<Light>& lights,
                    const std::vector<size_t>& owner, VolumeCounting method, const FrameOptions& options,
                    std::vector<VolumeDraw>& volumes) {
  const VolumeViewMode mode = options.volumeView;
  RenderState state = base;
  state.depthTest = true;
  state.depthFunc = CompareFunc::Less;
  state.depthWrite = false;
  state.blend = {true, BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha};
  auto culling = [&](CullMode cull) {
    state.cull = cull;
    return PassStates(state);
  };
  const PassStates overlay = culling(CullMode::None), backFaces = culling(CullMode::Front),
                   frontFaces = culling(CullMode::Back);
  const ConstantColorShader red({1.0, 0.0, 0.0, mode == VolumeViewMode::Overlay ? 0.3 : 0.45});
  const ConstantColorShader blue({0.0, 0.2, 1.0, 0.45});
  for (size_t l = 0; l < lights.size(); ++l) {
    const Light& light = lights[l];
    std::optional<ConstantColorShader> ownFront, ownBack;
    if (owner[l] < options.volumeColours.size()) {
      const std::array<glm::dvec3, 2>& c = options.volumeColours[owner[l]];
      ownFront.emplace(glm::dvec4(c[0], 0.45));
      ownBack.emplace(glm::dvec4(c[1], 0.45));
    }
    const ConstantColorShader& front = ownFront ? *ownFront : red;
    const ConstantColorShader& back = ownBack ? *ownBack : blue;
    std::vector<const PreparedInstance*> casters;
    for (const PreparedInstance& p : prepared)
      if (castsFor(p, light)) casters.push_back(&p);
    if (volumes.size() < casters.size()) volumes.resize(casters.size());
    for (size_t i = 0; i < casters.size(); ++i) {
      const PreparedInstance& p = *casters[i];
      const StencilCounting how = countingFor(method, *p.instance, scene, view, light);
      volumes[i].build(p, light, scene.shadow, how == StencilCounting::ZFail);
      if (mode == VolumeViewMode::Overlay) {
        volumes[i].drawAll(pipeline, overlay, p.index, &red);
        continue;
      }
      volumes[i].drawAll(pipeline, backFaces, p.index, &back);
      volumes[i].drawAll(pipeline, frontFaces, p.index, &front);
    }
    pipeline.endPass();
  }
}

// One warning per distinct shadow mesh the volumes do not cast as it is written, in the order of
// the instances that cast it.
void addCastingWarnings(std::span<const PreparedInstance> prepared, std::vector<std::string>& warnings) {
  std::vector<const Mesh*> seen;
  for (const PreparedInstance& p : prepared) {
    const Mesh* mesh = p.instance->shadowMesh;
    if (!mesh || std::find(seen.begin(), seen.end(), mesh) != seen.end()) continue;
    seen.push_back(mesh);
    std::string warning = castingWarning(*mesh);
    if (!warning.empty()) warnings.push_back(std::move(warning));
  }
}

std::string lightNote(size_t index, const Light& light, const LightTotals& t, const RasterStats& before,
                      const RasterStats& after) {
  using std::to_string;
  std::string s = "light L" + to_string(index) + " '" + light.name + "': " + to_string(t.objects) + " casters (" +
                  to_string(t.zpass) + " z-pass, " + to_string(t.zfail) + " z-fail), silhouette edges " +
                  to_string(t.volume.silhouetteEdges) + ", side triangles " + to_string(t.volume.sideTriangles) +
                  ", front cap " + to_string(t.volume.frontCapTriangles) + ", back cap " +
                  to_string(t.volume.backCapTriangles) + ", volume fragments " +
                  to_string(after.fragments - before.fragments) + ", stencil writes " +
                  to_string(after.stencilWrites - before.stencilWrites);
  if (!t.zfailObjects.empty()) {
    s += "\n  auto chose z-fail for:";
    for (const std::string& path : t.zfailObjects) s += " '" + path + "'";
  }
  return s;
}

}  // namespace

RenderState volumeBaseState(const SceneView& view) {
  RenderState base;
  base.viewport = view.viewport;
  base.clipFar = false;
  base.cull = CullMode::Back;
  base.depthTest = true;
  base.depthFunc = CompareFunc::Less;
  return base;
}

void renderShadowVolumes(const Scene& scene, VolumeCounting method, const FrameOptions& options, FrameResult& result,
                         Pipeline& pipeline) {
  // Volumes reach infinity: P_inf, no far clipping ([Kuhn 2016, §3.3]).
  const SceneView view = makeCameraView(scene, true);
  const std::vector<Instance> instances = scene.instances();
  const std::vector<PreparedInstance> prepared = prepareInstances(instances, view, &pipeline);
  addCastingWarnings(prepared, result.warnings);
  int passCounter = 0;
  // Every pass ends inside fn (drawLit, drawVolumePass, drawVolumeView end theirs).
  auto pass = [&](const std::string& what, auto&& fn) {
    const auto start = std::chrono::steady_clock::now();
    fn();
    const std::string name = numberedPass(passCounter, what);
    result.timings.push_back({name, millisecondsSince(start)});
    if (options.onPass) options.onPass(name, pipeline.framebuffer());
  };

  const RenderState base = volumeBaseState(view);

  std::vector<Light> lights;  // soft lights expanded ([Kuhn 2016, §3.6])
  std::vector<size_t> owner;  // the scene light each came from
  for (size_t s = 0; s < scene.lights.size(); ++s)
    for (const Light& l : expandSoftLight(scene.lights[s])) {
      lights.push_back(l);
      owner.push_back(s);
    }
  std::optional<VisibilityCounts> visibility;
  if (options.keepVisibility) visibility.emplace(scene.lights.size(), pipeline.framebuffer().pixelCount());

  const bool darken = scene.shadow.darkenComposite;
  pass(darken ? "lit" : "ambient", [&] {
    pipeline.clear({.state = base, .color = glm::vec4(glm::vec3(scene.background), 1.0f), .depth = 1.0});
    if (darken) drawLit(pipeline, base, scene, view, prepared, lights, true, DrawKind::Lit);
    else drawAmbient(pipeline, base, scene, view, prepared);
  });

  RenderState volumeBase = base;
  RenderState composite = base;
  composite.depthFunc = CompareFunc::LEqual;
  composite.depthWrite = false;
  composite.stencilTest = true;
  for (StencilFaceState& s : composite.stencil) {
    s.func = darken ? CompareFunc::NotEqual : CompareFunc::Equal;
    s.ref = 0;
  }
  if (!darken) composite.blend = {true, BlendFactor::One, BlendFactor::One};

  // One per caster of a light, kept from light to light for the frame: a caster's volume reuses
  // the buffers it grew for the light before. Each light rebuilds what it draws, once the pass
  // that drew the volumes before has ended.
  std::vector<VolumeDraw> volumes;
  for (size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    const std::string suffix = "L" + std::to_string(i);
    LightTotals totals;
    const RasterStats before = pipeline.stats();
    pass("stencil-" + suffix, [&] {
      pipeline.clear({.state = base, .stencil = 0});
      totals = drawVolumePass(pipeline, volumeBase, scene, view, prepared, light, method, volumes);
    });
    result.notes.push_back(lightNote(i, light, totals, before, pipeline.stats()));
    if (options.keepStencil) {
      result.stencilPerLight.push_back(pipeline.framebuffer().stencil());
      result.stencilLightNames.push_back(suffix);
    }
    // Visibility of a volume method: the count this light's volumes left, 0 = lit.
    if (visibility) visibility->addStencil(owner[i], pipeline.framebuffer().stencil());
    pass((darken ? "darken-" : "lit-") + suffix, [&] {
      if (darken) drawAmbient(pipeline, composite, scene, view, prepared, DrawKind::Darken);
      else drawLit(pipeline, composite, scene, view, prepared, std::span<const Light>(&light, 1), false);
    });
  }

  if (visibility) result.visibility = visibility->finish();

  if (options.volumeView != VolumeViewMode::None) {
    pass(options.volumeView == VolumeViewMode::Overlay ? "volumes-overlay" : "volumes", [&] {
      drawVolumeView(pipeline, base, scene, view, prepared, lights, owner, method, options, volumes);
    });
  }
}

// The techniques of this file (technique_registry.cpp lists them). They differ only in how the
// casters' volumes are counted, and read the same settings.
namespace {

constexpr TechniqueSetting kVolumeSettings[] = {
    {"silhouette", "kuhn, yen_kwoon, kilgard, lengyel"},
    {"two_sided", "true or false"},
    {"wrap", "true or false"},
    {"darken_composite", "true or false"},
};

std::string describeVolumeSettings(const ShadowSettings& s) {
  return "silhouette " + std::string(enumName(silhouetteNames(), s.silhouette)) + ", " +
         (s.twoSidedStencil ? "two-sided stencil" : "two culled passes") + ", " +
         (s.wrapOps ? "wrapping" : "saturating") + " stencil ops" + (s.darkenComposite ? ", darken compositing" : "");
}

template <VolumeCounting counting>
void renderVolumesCounting(const Scene& scene, const FrameOptions& options, FrameResult& result, Pipeline& pipeline) {
  renderShadowVolumes(scene, counting, options, result, pipeline);
}

}  // namespace

extern const ShadowTechnique kZPassTechnique{
    .name = "zpass",
    .summary = "stencil shadow volumes counted from the eye (z-pass) [Heidmann 1991], [Kuhn 2016, §3.2]",
    .settings = kVolumeSettings,
    .countsInStencil = true,
    .drawsVolumes = true,
    .render = renderVolumesCounting<VolumeCounting::ZPass>,
    .describe = describeVolumeSettings,
};

extern const ShadowTechnique kZFailTechnique{
    .name = "zfail",
    .summary = "stencil shadow volumes counted behind the surface, capped (z-fail) [Everitt & Kilgard 2002], [Kuhn 2016, §3.4]",
    .settings = kVolumeSettings,
    .countsInStencil = true,
    .drawsVolumes = true,
    .render = renderVolumesCounting<VolumeCounting::ZFail>,
    .describe = describeVolumeSettings,
};

extern const ShadowTechnique kAutoTechnique{
    .name = "auto",
    .summary = "stencil shadow volumes, z-fail only for the casters in the occlusion pyramid [McGuire et al. 2003], [Kuhn 2016, §4.2.1]",
    .settings = kVolumeSettings,
    .countsInStencil = true,
    .drawsVolumes = true,
    .render = renderVolumesCounting<VolumeCounting::PerCaster>,
    .describe = describeVolumeSettings,
};

}  // namespace shadowref
