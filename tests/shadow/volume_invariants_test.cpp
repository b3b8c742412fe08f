// Two exact invariants of stencil counting, on every scene in scenes/:
//
//  1. For the same capped volumes, z-fail = z-pass + (back − front fragments at the pixel, depth
//     ignored). Every volume fragment either passes or fails the depth test: z-pass counts
//     F_pass − B_pass, z-fail counts B_fail − F_fail, so their difference is B − F over all
//     fragments ([Kuhn 2016, §3.2 vs §3.4]). It holds only if the depth test, the facing and the
//     two-sided stencil treat every fragment consistently.
//  2. The silhouette volume counts the same as the union of one small volume per light-facing
//     triangle (buildTriangleVolumes): the interior quads come in pairs of opposite orientation
//     and cancel — exactly, if the rasterization is watertight ([Kuhn 2016, §3.5]). For the open,
//     non-manifold and inside-out meshes of tent.yaml and irregular.yaml, the volume with the
//     edges counted per side (volume_casting.h) against the per-triangle volumes it stands for.
//
// The volumes are drawn here through the raster pipeline directly, with the clip vertices made
// exactly as volume_renderer.cpp makes them (PreparedInstance::transform.toClip of the volume's
// object-space vertices), over the depth buffer of the frame renderer's ambient pass. Counts are
// compared as 8-bit wrapping values, i.e. modulo 256, on every pixel.
#include <span>
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "gl/pipeline.h"
#include "scene/scene_loader.h"
#include "shadow/facing.h"
#include "shadow/frame_renderer.h"
#include "shadow/scene_passes.h"
#include "shadow/scene_view.h"
#include "shadow/shadow_volume.h"
#include "shadow/soft_lights.h"
#include "shadow/stencil_counting.h"
#include "shadow/volume_renderer.h"

using namespace shadowref;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr int kWidth = 80, kHeight = 64;
#else
constexpr int kWidth = 200, kHeight = 160;
#endif

// Every scene file in scenes/, sorted, so a new scene is covered without editing this test.
std::vector<std::string> allSceneFiles() {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SHADOWREF_SOURCE_DIR) + "/scenes"))
    if (entry.path().extension() == ".yaml") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

Scene sceneForInvariants(const std::string& path) {
  LoadOptions options;
  options.overrides = {"image.width=" + std::to_string(kWidth), "image.height=" + std::to_string(kHeight)};
  Scene scene = loadScene(path, options);
  // The invariants are statements about counts modulo 256: wrapping ops ([SV slides]).
  scene.shadow.wrapOps = true;
  return scene;
}

// One volume of one caster, in clip space as volume_renderer.cpp draws it.
struct ClipVolume {
  std::vector<ClipVertex> vertices;
  std::vector<uint32_t> indices;  // every part: sides, front cap, back cap
};

ClipVolume toClip(const ShadowVolume& volume, const PreparedInstance& p) {
  ClipVolume c;
  c.vertices.resize(volume.positions.size());
  for (size_t i = 0; i < volume.positions.size(); ++i) c.vertices[i].position = p.transform.toClip(volume.positions[i]);
  for (VolumePart part : {VolumePart::Side, VolumePart::FrontCap, VolumePart::BackCap})
    for (const glm::uvec3& t : volume.part(part)) c.indices.insert(c.indices.end(), {t.x, t.y, t.z});
  return c;
}

enum class VolumeKind { Silhouette, PerTriangle };

// The volumes of every caster of `light`: built like the renderer's (its silhouette algorithm,
// light in object space) or as per-triangle volumes.
std::vector<ClipVolume> clipVolumes(const Scene& scene, const std::vector<PreparedInstance>& prepared,
                                    const Light& light, VolumeKind kind, bool withCaps) {
  std::vector<ClipVolume> out;
  for (const PreparedInstance& p : prepared) {
    if (!p.instance->shadowMesh || !withinRange(light, p.instance->worldBounds)) continue;
    const glm::dvec4 objectLight = lightInObjectSpace(p.instance->world, light.homogeneous());
    const ShadowVolume volume =
        kind == VolumeKind::Silhouette
            ? buildShadowVolume(*p.instance->shadowMesh, objectLight, scene.shadow.silhouette, withCaps)
            : buildTriangleVolumes(*p.instance->shadowMesh, objectLight, withCaps);
    out.push_back(toClip(volume, p));
  }
  return out;
}


// Depth test off, INCR_WRAP on back faces, DECR_WRAP on front faces: B − F at every pixel.
RenderState backMinusFrontState(const RenderState& base) {
  RenderState s = base;
  s.depthTest = false;
  s.depthWrite = false;
  s.cull = CullMode::None;
  s.colorMask = {false, false, false, false};
  s.stencilTest = true;
  for (Facing face : {FrontFacing, BackFacing}) {
    StencilFaceState& f = s.stencil[face];
    f.func = CompareFunc::Always;
    f.dppass = face == BackFacing ? StencilOp::IncrWrap : StencilOp::DecrWrap;
  }
  return s;
}

// Draws `volumes` with `states` (each volume with every state in turn, as the renderer does)
// into a copy of `depthSource` with the stencil cleared; returns the stencil.
PixelVector<uint8_t> countStencil(const Framebuffer& depthSource, const std::vector<ClipVolume>& volumes,
                                  const std::vector<RenderState>& states) {
  Framebuffer fb = depthSource;
  fb.ensureStencil();
  std::fill(fb.stencil().begin(), fb.stencil().end(), uint8_t(0));
  const auto pipeline = makePipeline(PipelineKind::Fast, fb, 0);
  for (const ClipVolume& v : volumes)
    for (const RenderState& state : states) {
      DrawCall call;
      call.state = &state;
      call.vertices = v.vertices;
      call.indices = v.indices;
      pipeline->draw(call);
    }
  return pipeline->framebuffer().stencil();
}

std::vector<RenderState> counting(const RenderState& base, StencilCounting how, const Scene& scene) {
  return volumePassStates(base, how, CountingOptions{scene.shadow.twoSidedStencil, true});
}

// "" when equal, else how many pixels differ and the first few: "3 pixels differ: 12,40: 1 vs 0; ..."
std::string differingPixels(std::span<const uint8_t> a, std::span<const uint8_t> b, int width) {
  if (a.size() != b.size()) return "different sizes";
  size_t count = 0;
  std::ostringstream first;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i] == b[i]) continue;
    if (count++ < 5)
      first << (i % width) << "," << (i / width) << ": " << int(int8_t(a[i])) << " vs " << int(int8_t(b[i])) << "; ";
  }
  return count == 0 ? "" : std::to_string(count) + " pixels differ: " + first.str();
}

size_t nonZeroCount(std::span<const uint8_t> s) {
  return static_cast<size_t>(std::count_if(s.begin(), s.end(), [](uint8_t v) { return v != 0; }));
}

// The frame renderer's z-fail frame: its depth buffer (the ambient pass's) and its stencils.
FrameResult zfailFrame(const Scene& scene) {
  FrameOptions options;
  options.method = "zfail";
  options.keepStencil = true;
  return renderFrame(scene, options);
}

std::vector<Light> drawnLights(const Scene& scene) {
  std::vector<Light> lights;
  for (const Light& light : scene.lights)
    for (const Light& l : expandSoftLight(light)) lights.push_back(l);
  return lights;
}

}  // namespace

TEST_CASE("invariant: z-fail = z-pass + (back - front fragments, depth ignored) for the same capped volumes, on every "
          "scene", "[volumes-oracle]") {
  const std::vector<std::string> files = allSceneFiles();
  REQUIRE(files.size() >= 8);
  size_t scenesWithShadow = 0, scenesWithEyeInVolume = 0;
  for (const std::string& file : files) {
    const Scene scene = sceneForInvariants(file);
    const FrameResult frame = zfailFrame(scene);
    const SceneView view = makeCameraView(scene, true);
    const std::vector<Instance> instances = scene.instances();
    const std::vector<PreparedInstance> prepared = prepareInstances(instances, view);
    const RenderState base = volumeBaseState(view);
    const std::vector<Light> lights = drawnLights(scene);
    REQUIRE(frame.stencilPerLight.size() == lights.size());
    for (size_t l = 0; l < lights.size(); ++l) {
      const std::vector<ClipVolume> volumes = clipVolumes(scene, prepared, lights[l], VolumeKind::Silhouette, true);
      const PixelVector<uint8_t> zpass = countStencil(frame.framebuffer, volumes, counting(base, StencilCounting::ZPass, scene));
      const PixelVector<uint8_t> zfail = countStencil(frame.framebuffer, volumes, counting(base, StencilCounting::ZFail, scene));
      const PixelVector<uint8_t> backMinusFront = countStencil(frame.framebuffer, volumes, {backMinusFrontState(base)});
      std::vector<uint8_t> predicted(zpass.size());
      for (size_t i = 0; i < zpass.size(); ++i) predicted[i] = uint8_t(zpass[i] + backMinusFront[i]);

      INFO(file << " light " << l);
      // These are the renderer's volumes: the same z-fail stencil, byte for byte.
      CHECK(differingPixels(zfail, frame.stencilPerLight[l], scene.width) == "");
      CHECK(differingPixels(zfail, predicted, scene.width) == "");
      scenesWithShadow += nonZeroCount(zfail) > 0;
      // B - F is the number of volumes containing the eye: non-zero only at the pumpkins.
      scenesWithEyeInVolume += nonZeroCount(backMinusFront) > 0;
    }
  }
  CHECK(scenesWithShadow >= files.size() / 2);  // not vacuous: volumes reach the pixels
  CHECK(scenesWithEyeInVolume >= 1);            // and z-pass differs from z-fail somewhere
}

TEST_CASE("invariant: the silhouette volume counts exactly like the per-triangle volumes of every light-facing "
          "triangle (interior quads cancel), z-pass and z-fail, on every scene", "[volumes-oracle]") {
  // Regression: the two quads of an interior edge used to be cut along different diagonals, and
  // at pumpkins 200x160 one pixel differed (extrusion.cpp now picks the diagonal by vertex index).
  for (const std::string& file : allSceneFiles()) {
    const Scene scene = sceneForInvariants(file);
    const FrameResult frame = zfailFrame(scene);
    const SceneView view = makeCameraView(scene, true);
    const std::vector<Instance> instances = scene.instances();
    const std::vector<PreparedInstance> prepared = prepareInstances(instances, view);
    const RenderState base = volumeBaseState(view);
    for (const Light& light : drawnLights(scene)) {
      INFO(file << " light '" << light.name << "'");
      // z-pass draws the sides (and the front caps of the meshes not cast as written,
      // volume_casting.h), z-fail the capped volumes: each as the renderer would.
      for (StencilCounting how : {StencilCounting::ZPass, StencilCounting::ZFail}) {
        const bool caps = how == StencilCounting::ZFail;
        const std::vector<RenderState> states = counting(base, how, scene);
        const PixelVector<uint8_t> silhouette =
            countStencil(frame.framebuffer, clipVolumes(scene, prepared, light, VolumeKind::Silhouette, caps), states);
        const PixelVector<uint8_t> perTriangle =
            countStencil(frame.framebuffer, clipVolumes(scene, prepared, light, VolumeKind::PerTriangle, caps), states);
        INFO(name(how));
        CHECK(differingPixels(silhouette, perTriangle, scene.width) == "");
      }
    }
  }
}
