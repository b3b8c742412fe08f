// Animation tracks: interpolation against values computed by hand, the `animation:` section's
// errors (file:line:col), and the scene at time t rendering the same bytes as a still scene file
// that writes the values of that time.
#include <catch2/catch.hpp>

#include <cstring>

#include "scene/animation.h"
#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"
#include "support/errors.h"

using namespace shadowref;
using shadowref::testing::messageOf;
using shadowref::testing::yamlErrorOf;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

Track<double> scalarTrack(Interpolation interpolation, std::vector<double> times, std::vector<double> values) {
  Track<double> t;
  t.interpolation = interpolation;
  t.times = std::move(times);
  t.values = std::move(values);
  return t;
}

// A box under a light, 48 x 32, z-fail shadow volumes: small enough to render in milliseconds.
const std::string kStill =
    "image: {width: 48, height: 32}\n"
    "camera: {eye: [0, 1, 5], target: [0, 0, 0]}\n"
    "lights:\n"
    "  - {name: lamp, position: [0, 4, 0]}\n"
    "meshes:\n"
    "  box: {box: {}}\n"
    "  floor: {plane: {size: [8, 8]}}\n"
    "nodes:\n"
    "  - {name: floor, mesh: floor, translate: [0, -1, 0]}\n"
    "  - {name: crate, mesh: box, translate: [0, 0, 0]}\n"
    "shadow: {method: zfail}\n";

}  // namespace

TEST_CASE("a linear track is the straight line between its keys", "[animation]") {
  Track<glm::dvec3> track;
  track.times = {0.0, 2.0};
  track.values = {glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(2.0, 4.0, -6.0)};
  CHECK(evaluate(track, 1.0) == glm::dvec3(1.0, 2.0, -3.0));  // the midpoint
  CHECK(evaluate(track, 0.5) == glm::dvec3(0.5, 1.0, -1.5));
  // Held outside the keys.
  CHECK(evaluate(track, -3.0) == glm::dvec3(0.0));
  CHECK(evaluate(track, 7.0) == glm::dvec3(2.0, 4.0, -6.0));
  const Track<double> one = scalarTrack(Interpolation::Linear, {1.5}, {42.0});
  CHECK(evaluate(one, 0.0) == 42.0);
  CHECK(evaluate(one, 9.0) == 42.0);
}

TEST_CASE("a smooth track between two keys is smoothstep", "[animation]") {
  const Track<double> track = scalarTrack(Interpolation::Smooth, {0.0, 2.0}, {0.0, 10.0});
  CHECK(evaluate(track, 0.0) == 0.0);
  CHECK(evaluate(track, 2.0) == 10.0);
  CHECK(evaluate(track, 1.0) == 5.0);                          // 3/4 - 2/8 = 1/2
  CHECK(evaluate(track, 0.5) == Approx(1.5625).epsilon(1e-15));  // s = 1/4: 3/16 - 2/64 = 5/32
  CHECK(evaluate(track, 1.5) == Approx(8.4375).epsilon(1e-15));  // s = 3/4: 27/16 - 54/64 = 27/32
  // At rest at both ends: the slope tends to 0 (p(e) - p(0) = 10 (3 (e/2)^2 - 2 (e/2)^3)).
  const double e = 1e-4;
  CHECK(std::abs(evaluate(track, e) - evaluate(track, 0.0)) / e < 1e-3);
  CHECK(std::abs(evaluate(track, 2.0) - evaluate(track, 2.0 - e)) / e < 1e-3);
}

TEST_CASE("a smooth track has Catmull-Rom tangents at inner keys and passes through every key", "[animation]") {
  // Keys (0, 0), (1, 1), (3, 5): the tangent at t = 1 is (5 - 0) / (3 - 0) = 5/3 per second.
  const Track<double> track = scalarTrack(Interpolation::Smooth, {0.0, 1.0, 3.0}, {0.0, 1.0, 5.0});
  CHECK(evaluate(track, 0.0) == 0.0);
  CHECK(evaluate(track, 1.0) == 1.0);
  CHECK(evaluate(track, 3.0) == 5.0);
  const double e = 1e-6;
  CHECK((evaluate(track, 1.0 + e) - evaluate(track, 1.0 - e)) / (2 * e) == Approx(5.0 / 3.0).epsilon(1e-6));
  // t = 2, s = 1/2 of [1, 3], h = 2: h00 = h01 = 1/2, h10 = 1/8, h11 = -1/8, m = 5/3 and 0:
  // 1/2 + 2 (1/8)(5/3) + 5/2 = 41/12.
  CHECK(evaluate(track, 2.0) == Approx(41.0 / 12.0).epsilon(1e-15));
  // t = 0.5 in [0, 1], h = 1, m0 = 0, m1 = 5/3: h01 = 1/2, h11 = -1/8: 1/2 - 5/24 = 7/24.
  CHECK(evaluate(track, 0.5) == Approx(7.0 / 24.0).epsilon(1e-15));
}

TEST_CASE("an on/off track steps at its keys", "[animation]") {
  Track<bool> on;
  on.interpolation = Interpolation::Step;
  on.times = {0.0, 1.0, 2.0};
  on.values = {true, false, true};
  CHECK(evaluate(on, -1.0));
  CHECK(evaluate(on, 0.999));
  CHECK_FALSE(evaluate(on, 1.0));
  CHECK_FALSE(evaluate(on, 1.5));
  CHECK(evaluate(on, 2.0));
}

TEST_CASE("a scene without animation is unchanged by sceneAt", "[animation]") {
  const Scene scene = loadSceneFromString(kStill, "still.yaml");
  CHECK(scene.animation == nullptr);
  const Scene at = sceneAt(scene, 3.0);
  CHECK(at.camera.eye == scene.camera.eye);
  CHECK(at.lights.size() == scene.lights.size());
}

TEST_CASE("frame t of an animated scene renders the bytes of a still file with those values", "[animation]") {
  const std::string animated = kStill +
                               "animation:\n"
                               "  fps: 4\n"
                               "  camera:\n"
                               "    eye: {keys: {0: [0, 1, 5], 2: [2, 3, 5]}}\n"
                               "  lights:\n"
                               "    lamp:\n"
                               "      position: {keys: {0: [0, 4, 0], 2: [2, 4, 2]}}\n"
                               "      color: {interpolation: smooth, keys: {0: [1, 1, 1], 2: [1, 0.5, 0]}}\n"
                               "  nodes:\n"
                               "    crate: {rotate: {keys: {0: [0, 0, 0], 2: [0, 90, 0]}}}\n";
  const Scene scene = loadSceneFromString(animated, "anim.yaml");
  REQUIRE(scene.animation);
  CHECK(scene.animation->fps == 4.0);
  CHECK(scene.animation->lastKeyTime() == 2.0);
  // t = 1: the linear midpoints, and smoothstep(1/2) = 1/2 for the colour.
  std::string still = kStill;
  still.replace(still.find("eye: [0, 1, 5]"), 14, "eye: [1, 2, 5]");
  still.replace(still.find("position: [0, 4, 0]"), 19, "position: [1, 4, 1], color: [1, 0.75, 0.5]");
  still.replace(still.find("translate: [0, 0, 0]"), 20, "translate: [0, 0, 0], rotate: {euler: [0, 45, 0]}");
  const Scene expected = loadSceneFromString(still, "still.yaml");
  const Scene frame = sceneAt(scene, 1.0);
  CHECK(frame.animation == nullptr);
  CHECK(frame.camera.eye == expected.camera.eye);
  CHECK(frame.lights[0].color == expected.lights[0].color);
  const FrameResult a = renderFrame(frame);
  const FrameResult b = renderFrame(expected);
  const FrameResult first = renderFrame(sceneAt(scene, 0.0));
  const auto& ca = a.framebuffer.color();
  const auto& cb = b.framebuffer.color();
  REQUIRE(ca.size() == cb.size());
  CHECK(std::memcmp(ca.data(), cb.data(), ca.size() * sizeof(ca[0])) == 0);
  CHECK(a.framebuffer.stencil() == b.framebuffer.stencil());
  // And the animation does move: frame 0 differs.
  CHECK(std::memcmp(ca.data(), first.framebuffer.color().data(), ca.size() * sizeof(ca[0])) != 0);
}

TEST_CASE("a light's on track leaves it out of the frame", "[animation]") {
  const Scene scene = loadSceneFromString(kStill + "animation:\n  lights:\n    lamp: {on: {keys: {0: true, 1: false}}}\n",
                                          "anim.yaml");
  CHECK(sceneAt(scene, 0.5).lights.size() == 1);
  CHECK(sceneAt(scene, 1.0).lights.empty());
}

TEST_CASE("tracks of a light or node that -D turned off are skipped", "[animation]") {
  const std::string animated = kStill +
                               "animation:\n"
                               "  lights: {lamp: {position: {keys: {0: [0, 4, 0], 2: [2, 4, 2]}}}}\n"
                               "  nodes: {crate: {rotate: {keys: {0: [0, 0, 0], 2: [0, 90, 0]}}}}\n";
  LoadOptions off;
  off.overrides = {"lights.lamp=off", "nodes.crate=off"};
  const Scene scene = loadSceneFromString(animated, "anim.yaml", off);
  REQUIRE(scene.animation);
  CHECK(scene.animation->lights.empty());
  CHECK(scene.animation->nodes.empty());
  const Scene frame = sceneAt(scene, 1.0);
  CHECK(frame.lights.empty());
  REQUIRE(frame.roots.size() == 1);
  CHECK(frame.roots[0].name == "floor");
}

TEST_CASE("animation section errors point at the key", "[animation]") {
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  cameras: {}\n"),
             StartsWith("t.yaml:13:3: ") && Contains("cameras") && Contains("camera"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  camera:\n    eye: {keys: {1: [0, 1, 5], 0.5: [0, 2, 5]}}\n"),
             StartsWith("t.yaml:14:32: ") && Contains("increase"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  lights:\n    lmap: {color: {keys: {0: 1}}}\n"),
             StartsWith("t.yaml:14:5: ") && Contains("no light named 'lmap'") && Contains("did you mean 'lamp'"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  interpolation: smoth\n"),
             StartsWith("t.yaml:13:18: ") && Contains("did you mean 'smooth'"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  camera: {fov: {keys: {0: 190}}}\n"),
             StartsWith("t.yaml:13:28: ") && Contains("between 0 and 180"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  nodes:\n    crat: {scale: {keys: {0: 2}}}\n"),
             StartsWith("t.yaml:14:5: ") && Contains("no node with the path 'crat'") && Contains("did you mean 'crate'"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  lights:\n    lamp: {on: {interpolation: linear, keys: {0: true}}}\n"),
             StartsWith("t.yaml:14:17: ") && Contains("interpolation"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  fps: 0\n"), StartsWith("t.yaml:13:8: ") && Contains("fps"));
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  camera: {eye: {keys: {}}}\n"),
             StartsWith("t.yaml:13:24: ") && Contains("at least one"));
  // A directional light has no position to move.
  const std::string sun = "lights:\n  - {name: sun, type: directional, direction: [0, -1, 0]}\n";
  CHECK_THAT(yamlErrorOf(sun + "animation:\n  lights:\n    sun: {position: {keys: {0: [0, 1, 0]}}}\n"),
             StartsWith("t.yaml:5:11: ") && Contains("directional light has no position"));
}

TEST_CASE("two nodes of the same path cannot be animated apart", "[animation]") {
  std::string twice = kStill;
  twice.insert(twice.find("shadow:"), "  - {name: crate, mesh: box, translate: [2, 0, 0]}\n");
  CHECK_THAT(yamlErrorOf(twice + "animation:\n  nodes:\n    crate: {translate: {keys: {0: [0, 1, 0]}}}\n"),
             StartsWith("t.yaml:15:5: ") && Contains("2 nodes have the path 'crate'"));
}

TEST_CASE("a frame whose camera meets its target is an error naming the time", "[animation]") {
  // Checked at load for the first and the last key.
  CHECK_THAT(yamlErrorOf(kStill + "animation:\n  camera: {eye: {keys: {0: [0, 1, 5], 2: [0, 0, 0]}}}\n"),
             StartsWith("t.yaml:13:17: ") && Contains("same point") && Contains("t = 2 s"));
  // Between keys, when the frame is made: the eye passes through the target at t = 1.
  const Scene scene = loadSceneFromString(
      kStill + "animation:\n  camera: {eye: {keys: {0: [0, -1, -5], 2: [0, 1, 5]}}}\n", "t.yaml");
  CHECK_THAT(messageOf([&] { sceneAt(scene, 1.0); }), StartsWith("t.yaml:13:17: ") && Contains("t = 1 s"));
}
