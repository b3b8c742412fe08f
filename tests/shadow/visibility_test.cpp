// Per-light visibility (shadow/visibility.h) as each method defines it: hand-computed pixels of a
// box over a plane, the stencil methods agreeing with each other, the reference and the fast
// pipeline giving the same values, and fractions only where PCF or a soft light makes them.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"

using namespace shadowref;

namespace {

// A unit box floating over a plane (its bottom at y = 0.5, its top at 1.5), seen straight down
// from (0, 10, 0) with a 60° field of view: screen right is +x, screen up is -z. Pixel column c
// looks at x = ((c + 0.5) / 32 - 1) · 10 tan 30° on the plane, row r at z = -((r + 0.5) / 32 - 1) ·
// 10 tan 30°. The light travels along (1, -1, 0), so the box's shadow on the plane is the
// rectangle x ∈ [0, 2], z ∈ [-0.5, 0.5] (a point at height y lands at x + y); the box itself hides
// the plane up to x = 0.5 · 10 / 8.5 ≈ 0.59 from the camera.
std::string boxOverPlane(const std::string& method, const std::string& light, const std::string& extra = "") {
  return "image: {width: 64, height: 64}\n"
         "camera: {eye: [0, 10, 0], target: [0, 0, 0], up: [0, 0, -1], fov: 60}\n"
         "lights:\n  - " + light + "\n"
         "meshes:\n  ground: {plane: {size: [10, 10]}}\n  box: {box: {size: [1, 1, 1]}}\n"
         "nodes:\n  - {name: ground, mesh: ground}\n  - {name: box, mesh: box, translate: [0, 1, 0]}\n"
         "shadow: {method: " + method + extra + "}\n";
}

const std::string kSun = "{name: sun, type: directional, direction: [1, -1, 0]}";

FrameResult render(const std::string& yaml, PipelineKind pipeline = PipelineKind::Fast, int threads = 2) {
  const Scene scene = loadSceneFromString(yaml, "t.yaml");
  FrameOptions options;
  options.keepVisibility = true;
  options.pipeline = pipeline;
  options.threads = threads;
  return renderFrame(scene, options);
}

float at(const FrameResult& f, int x, int y) { return f.visibility.at(0).at(size_t(y) * 64 + size_t(x)); }

const char* kMethods[] = {"none", "zpass", "zfail", "auto", "shadowmap", "tsm"};

}  // namespace

TEST_CASE("visibility: hand-computed pixels of a box over a plane, every method", "[visibility]") {
  for (const char* method : kMethods) {
    INFO(method);
    const FrameResult f = render(boxOverPlane(method, kSun));
    REQUIRE(f.visibility.size() == 1);
    REQUIRE(f.visibility[0].size() == 64 * 64);
    const float shadowed = std::string(method) == "none" ? 1.0f : 0.0f;
    // In the shadow: x = 1.17 ... 1.53, z = ±0.09.
    for (int x = 38; x <= 40; ++x)
      for (int y = 31; y <= 32; ++y) CHECK(at(f, x, y) == shadowed);
    CHECK(at(f, 24, 32) == 1.0f);  // x = -1.35: the plane on the light's side of the box
    CHECK(at(f, 40, 50) == 1.0f);  // z = -3.3: beside the shadow
    CHECK(at(f, 32, 32) == 1.0f);  // the box's top face
    CHECK(at(f, 0, 0) == 1.0f);    // x = z = -5.7: past the plane's edge, the background
    // Without PCF or soft lights a pixel sees the light or does not.
    for (float v : f.visibility[0]) REQUIRE((v == 0.0f || v == 1.0f));
  }
}

TEST_CASE("visibility: z-pass, z-fail and auto count the same shadows", "[visibility]") {
  const FrameResult zpass = render(boxOverPlane("zpass", kSun));
  CHECK(render(boxOverPlane("zfail", kSun)).visibility == zpass.visibility);
  CHECK(render(boxOverPlane("auto", kSun)).visibility == zpass.visibility);
  // The room of [Kuhn 2016, Fig. 5.1]: a point light, a table and chairs; the camera outside every
  // volume, where z-pass counts right.
  const std::string room = "generator: room\nimage: {width: 80, height: 64}\nshadow: {method: ";
  const FrameResult roomZpass = render(room + "zpass}\n");
  REQUIRE(roomZpass.visibility.size() == 1);
  CHECK(render(room + "zfail}\n").visibility == roomZpass.visibility);
  CHECK(render(room + "auto}\n").visibility == roomZpass.visibility);
  size_t shadowed = 0;
  for (float v : roomZpass.visibility[0]) shadowed += v == 0.0f;
  CHECK(shadowed > 0);  // the table's shadow is on the floor
}

TEST_CASE("visibility: the reference and the fast pipeline give the same values", "[visibility]") {
  for (const char* method : kMethods) {
    INFO(method);
    const std::string yaml = boxOverPlane(method, kSun, ", pcf: 3");
    CHECK(render(yaml, PipelineKind::Reference, 1).visibility == render(yaml, PipelineKind::Fast, 3).visibility);
  }
}

TEST_CASE("visibility: PCF gives fractions of k x k comparisons", "[visibility]") {
  for (const char* method : {"shadowmap", "tsm"}) {
    INFO(method);
    // A 128² map over the whole scene (a fitted map would hug the box, its texels smaller than a
    // pixel): a texel is about 0.12 units of the plane, so the shadow's edges get fractions.
    const std::string fit = std::string(method) == "shadowmap" ? ", fit: scene" : "";
    const FrameResult f = render(boxOverPlane(method, kSun, ", pcf: 3, map_size: 128" + fit));
    size_t between = 0;
    for (float v : f.visibility[0]) {
      REQUIRE(float(std::nearbyint(double(v) * 9.0) / 9.0) == v);  // a multiple of 1/9, as float
      between += v > 0.0f && v < 1.0f;
    }
    CHECK(between > 0);
    CHECK(at(f, 39, 32) == 0.0f);  // the shadow's middle, over 3 texels from its edges: all nine fail
    CHECK(at(f, 0, 0) == 1.0f);    // the background
  }
}

TEST_CASE("visibility: a soft light's value is the fraction of its lights that see the pixel", "[visibility]") {
  // sphere14: 15 lights; the volumes of each counted on their own.
  const std::string soft = "{name: bulb, position: [-4, 4, 0], soft: {shape: sphere14, spacing: 0.3}}";
  for (const char* method : {"zfail", "shadowmap"}) {
    INFO(method);
    const FrameResult f = render(boxOverPlane(method, soft, ", map_size: 256"));
    REQUIRE(f.visibility.size() == 1);  // one channel for the scene's light, not fifteen
    size_t between = 0;
    for (float v : f.visibility[0]) {
      REQUIRE(float(std::nearbyint(double(v) * 15.0) / 15.0) == v);  // a multiple of 1/15
      between += v > 0.0f && v < 1.0f;
    }
    CHECK(between > 0);  // the penumbra
    CHECK(at(f, 24, 32) == 1.0f);
  }
}

TEST_CASE("visibility: one channel per light, in the scene's order", "[visibility]") {
  // The second light shines straight down: the box hides only what lies below it.
  const std::string two = boxOverPlane("zfail", kSun + "\n  - {name: top, type: directional, direction: [0, -1, 0]}");
  const FrameResult f = render(two);
  REQUIRE(f.visibility.size() == 2);
  CHECK(f.visibility[0][32 * 64 + 39] == 0.0f);  // in the sun's shadow
  CHECK(f.visibility[1][32 * 64 + 39] == 1.0f);  // but not in the top light's
  // Without keepVisibility nothing is computed.
  const Scene scene = loadSceneFromString(two, "t.yaml");
  CHECK(renderFrame(scene).visibility.empty());
}
