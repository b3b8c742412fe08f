// Every scene in scenes/ with every shadow technique of the registry, in both depth formats: the
// frame the fast executor renders at 1, 2, 3 and 8 threads must be the reference pipeline's, byte
// for byte — colour, depth codes, stencil and accumulation, the stencil after each light, the
// shadow maps — with the same statistics and the same per-light notes. A technique that refuses a
// scene must refuse it the same way in both. Frames are small (40 × 32, maps 64²) so that the
// whole grid runs in both builds; one test case per scene, so that ctest spreads them.
#include <catch2/catch.hpp>

#include <cstring>
#include <exception>
#include <filesystem>
#include <set>
#include <optional>
#include <string>
#include <vector>

#include "scene/animation.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "shadow/technique_registry.h"

using namespace shadowref;

namespace {

struct Outcome {
  std::optional<FrameResult> frame;
  std::string refusal;  // what() of the exception when the technique refused the scene
};

Outcome render(const Scene& scene, const std::string& technique, PipelineKind pipeline, int threads) {
  FrameOptions options;
  options.method = technique;
  options.pipeline = pipeline;
  options.threads = threads;
  options.keepStencil = true;
  options.keepShadowMaps = true;
  Outcome out;
  try {
    out.frame.emplace(renderFrame(scene, options));
  } catch (const std::exception& e) {
    out.refusal = e.what();
  }
  return out;
}

template <class Vector>
bool sameBytes(const Vector& a, const Vector& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

// The first thing that differs between the reference's frame and the fast one's; empty if none.
std::string firstDifference(const FrameResult& ref, const FrameResult& fast) {
  const Framebuffer &a = ref.framebuffer, &b = fast.framebuffer;
  if (!sameBytes(a.color(), b.color())) return "colour buffer";
  if (!sameBytes(a.depthCodes(), b.depthCodes())) return "depth buffer";
  if (!sameBytes(a.stencil(), b.stencil())) return "stencil buffer";
  if (!sameBytes(a.accum(), b.accum())) return "accumulation buffer";
  if (std::memcmp(&ref.stats, &fast.stats, sizeof(RasterStats)) != 0) return "statistics";
  if (ref.notes != fast.notes) return "per-light notes";
  if (ref.stencilPerLight.size() != fast.stencilPerLight.size()) return "number of per-light stencils";
  for (size_t i = 0; i < ref.stencilPerLight.size(); ++i)
    if (!sameBytes(ref.stencilPerLight[i], fast.stencilPerLight[i])) return "stencil after light " + std::to_string(i);
  if (ref.shadowMapNames != fast.shadowMapNames) return "shadow map names";
  for (size_t i = 0; i < ref.shadowMaps.size(); ++i)
    if (!sameBytes(ref.shadowMaps[i].values(), fast.shadowMaps[i].values())) return "shadow map " + ref.shadowMapNames[i];
  return {};
}

void checkScene(const std::string& file) {
  int rendered = 0;
  for (const char* depth : {"float32", "unorm24"}) {
    LoadOptions load;
    load.overrides = {"image.width=40", "image.height=32", "shadow.map_size=64", std::string("image.depth=") + depth};
    const Scene loaded = loadScene(std::string(SHADOWREF_SOURCE_DIR) + "/scenes/" + file, load);
    // An animated scene halfway through its keys: a frame, not only the values the file wrote.
    const Scene scene = sceneAt(loaded, loaded.animation ? loaded.animation->lastKeyTime() / 2 : 0.0);
    for (const ShadowTechnique* technique : techniques()) {
      const std::string name(technique->name);
      const Outcome ref = render(scene, name, PipelineKind::Reference, 1);
      for (const int threads : {1, 2, 3, 8}) {
        INFO(file << ", " << name << ", " << depth << " depth, fast pipeline at " << threads << " threads");
        const Outcome fast = render(scene, name, PipelineKind::Fast, threads);
        REQUIRE(fast.refusal == ref.refusal);
        if (!ref.frame) continue;
        CHECK(firstDifference(*ref.frame, *fast.frame) == "");
      }
      rendered += ref.frame.has_value();
    }
  }
  CHECK(rendered > 0);  // the scene rendered with at least one technique
}

}  // namespace

#define SCENE_FRAMES(scene)                                                                             \
  TEST_CASE("every technique on " scene ": the fast frames at 1, 2, 3, 8 threads are the reference's", \
            "[differential][scenes]") {                                                                 \
    checkScene(scene);                                                                                  \
  }

SCENE_FRAMES("anim_city_sunset.yaml")
SCENE_FRAMES("anim_pumpkins_walk.yaml")
SCENE_FRAMES("anim_room_circle.yaml")
SCENE_FRAMES("city.yaml")
SCENE_FRAMES("city16.yaml")
SCENE_FRAMES("city16_sun.yaml")
SCENE_FRAMES("directional.yaml")
SCENE_FRAMES("irregular.yaml")
SCENE_FRAMES("minimal.yaml")
SCENE_FRAMES("obj_example.yaml")
SCENE_FRAMES("outdoor.yaml")
SCENE_FRAMES("overflow.yaml")
SCENE_FRAMES("pumpkins.yaml")
SCENE_FRAMES("room.yaml")
SCENE_FRAMES("spot.yaml")
SCENE_FRAMES("tent.yaml")
SCENE_FRAMES("two_lights.yaml")

TEST_CASE("the scene grid names every scene in scenes/", "[differential][scenes]") {
  // A scene added to scenes/ must get its SCENE_FRAMES line above.
  const std::set<std::string> covered = {"anim_city_sunset.yaml", "anim_pumpkins_walk.yaml", "anim_room_circle.yaml",
                                         "city.yaml",     "city16.yaml",  "city16_sun.yaml", "directional.yaml",
                                         "irregular.yaml", "minimal.yaml", "obj_example.yaml", "outdoor.yaml",
                                         "overflow.yaml",  "pumpkins.yaml", "room.yaml",       "spot.yaml",
                                         "tent.yaml",      "two_lights.yaml"};
  std::set<std::string> present;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SHADOWREF_SOURCE_DIR) + "/scenes"))
    if (entry.path().extension() == ".yaml") present.insert(entry.path().filename().string());
  CHECK(present == covered);
}
