// -D reaching what the file made: removing a light or a node (`=off`), a node's shadow flags,
// material and mesh, a mesh's source; and the errors for names that are not there.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>
#include <vector>

#include "scene/scene_loader.h"
#include "shadow/frame_renderer.h"

using namespace shadowref;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

const std::string kHead =
    "image: {width: 48, height: 40}\n"
    "camera: {eye: [3, 4, 5], target: [0, 0.5, 0]}\n";
const std::string kKey = "  - {name: key, position: [2, 4, 1]}\n";
const std::string kFill = "  - {name: fill, type: spot, position: [-3, 3, 2], direction: [1, -1, -0.5], spot_cutoff: 40}\n";
const std::string kBody =
    "materials: {red: {diffuse: [0.8, 0.1, 0.1]}}\n"
    "meshes:\n  ground: {plane: {size: [8, 8]}}\n  box: {box: {}}\n  ball: {sphere: {radius: 0.4, slices: 12, stacks: 6}}\n"
    "nodes:\n"
    "  - {name: ground, mesh: ground}\n"
    "  - name: camp\n    children:\n"
    "      - {name: tent, mesh: box, translate: [0, 0.5, 0]}\n"
    "      - {name: ball, mesh: ball, translate: [1.2, 0.4, 0]}\n";

Scene load(const std::string& yaml, std::vector<std::string> overrides = {}) {
  LoadOptions options;
  options.overrides = std::move(overrides);
  return loadSceneFromString(yaml, "t.yaml", options);
}

std::string errorOf(const std::string& yaml, std::vector<std::string> overrides) {
  try {
    load(yaml, std::move(overrides));
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

template <class V>
bool sameBytes(const V& a, const V& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0);
}

// Every buffer of the two frames, byte for byte.
void requireSameFrame(const Scene& a, const Scene& b, const std::string& method) {
  FrameOptions options;
  options.method = method;
  options.keepVisibility = true;
  const FrameResult fa = renderFrame(a, options), fb = renderFrame(b, options);
  CHECK(sameBytes(fa.framebuffer.color(), fb.framebuffer.color()));
  CHECK(sameBytes(fa.framebuffer.depthCodes(), fb.framebuffer.depthCodes()));
  CHECK(sameBytes(fa.framebuffer.stencil(), fb.framebuffer.stencil()));
  CHECK(fa.visibility == fb.visibility);
}

}  // namespace

TEST_CASE("overrides: -D lights.NAME=off: two lights with one removed render as the one-light scene", "[overrides]") {
  const std::string two = kHead + "lights:\n" + kKey + kFill + kBody;
  const std::string one = kHead + "lights:\n" + kKey + kBody;
  const Scene removed = load(two, {"lights.fill=off"});
  REQUIRE(removed.lights.size() == 1);
  CHECK(removed.lights[0].name == "key");
  for (const char* method : {"none", "zpass", "zfail", "auto", "shadowmap", "tsm"}) {
    INFO(method);
    requireSameFrame(removed, load(one), method);
  }
  // By number, and 'false' as well as 'off'; the other light keeps its number meanwhile.
  const Scene byNumber = load(two, {"lights.0=false", "lights.1.spot_cutoff=30"});
  REQUIRE(byNumber.lights.size() == 1);
  CHECK(byNumber.lights[0].name == "fill");
  CHECK(byNumber.lights[0].spotCutoffDegrees == 30.0);
}

TEST_CASE("overrides: -D nodes.PATH: removing a node, its shadow flag, material and mesh", "[overrides]") {
  const std::string scene = kHead + "lights:\n" + kKey + kBody;
  // A removed group takes its children along.
  std::string withoutCamp = scene.substr(0, scene.find("  - name: camp"));
  requireSameFrame(load(scene, {"nodes.camp=off"}), load(withoutCamp), "zfail");
  const Scene noTent = load(scene, {"nodes.camp/tent=off"});
  REQUIRE(noTent.instances().size() == 2);
  CHECK(noTent.instances()[1].path == "camp/ball");

  std::string flagged = scene;
  flagged.replace(flagged.find("mesh: box,"), 10, "mesh: box, cast_shadows: false,");
  requireSameFrame(load(scene, {"nodes.camp/tent.cast_shadows=false"}), load(flagged), "zfail");
  requireSameFrame(load(scene, {"nodes.camp/tent.cast_shadows=false"}), load(flagged), "shadowmap");

  const Scene changed = load(scene, {"nodes.camp/ball.material=red", "nodes.camp/ball.mesh=box"});
  const std::vector<Instance> instances = changed.instances();
  REQUIRE(instances.size() == 3);
  CHECK(changed.materials[size_t(instances[2].material)].name == "red");
  CHECK(instances[2].mesh->name == "box");
}

TEST_CASE("overrides: -D meshes.NAME...: a key of the file's mesh source", "[overrides]") {
  const std::string scene = kHead + kBody;
  const Scene changed = load(scene, {"meshes.box.box.size=[1, 2, 1]"});
  std::string written = scene;
  written.replace(written.find("box: {box: {}}"), 14, "box: {box: {size: [1, 2, 1]}}");
  const Scene expected = load(written);
  CHECK(changed.meshes[1]->bounds.max == expected.meshes[1]->bounds.max);
  CHECK(changed.meshes[1]->bounds.max.y == 1.0);
  CHECK(load(scene, {"meshes.ball.normals=flat"}).meshes[2]->positions.size() ==
        3 * load(scene).meshes[2]->triangles.size());
}

TEST_CASE("overrides: -D naming a light, node or mesh that is not there is an error on the command line", "[overrides]") {
  const std::string scene = kHead + "lights:\n" + kKey + kFill + kBody;
  CHECK(errorOf(scene, {"lights.fil=off"}) ==
        "<command line>:1:8: lights.fil: no light named 'fil'; did you mean 'fill'?");
  CHECK_THAT(errorOf(scene, {"camera.fov=50", "lights.7.range=3"}),
             StartsWith("<command line>:2:8: lights.7: the scene has 2 light(s)"));
  CHECK(errorOf(scene, {"nodes.tent.cast_shadows=false"}) ==
        "<command line>:1:7: nodes.tent: no node with the path 'tent'; did you mean 'camp/tent'?");
  CHECK_THAT(errorOf(scene, {"nodes.camp/tnt=off"}), StartsWith("<command line>:1:7: nodes.camp/tnt: no node"));
  CHECK_THAT(errorOf(scene, {"nodes.camp/tent.translate=[1, 0, 0]"}),
             StartsWith("<command line>:1:17: unknown key 'translate' in nodes.camp/tent (allowed: mesh, material, "
                        "cast_shadows, shadow_proxy)"));
  CHECK_THAT(errorOf(scene, {"nodes.camp/tent.mesh=boxx"}),
             StartsWith("<command line>:1:22: nodes.camp/tent.mesh: no mesh named 'boxx'; did you mean 'box'?"));
  CHECK_THAT(errorOf(scene, {"meshes.bx.box.size=2"}),
             StartsWith("<command line>:1:8: meshes.bx: no mesh named 'bx' in the file's meshes section"));
  CHECK_THAT(errorOf(scene, {"lights.fill=on"}), StartsWith("<command line>:1:13: lights.fill: only 'off'"));
  CHECK_THAT(errorOf(scene, {"lights.fill=off", "lights.fill.range=2"}),
             StartsWith("<command line>:2:8: lights.fill: the light 'fill' was removed by an earlier -D"));
  CHECK_THAT(errorOf(scene, {"nodes.camp=off", "nodes.camp/ball=off"}),
             StartsWith("<command line>:2:7: nodes.camp/ball: the node was removed by an earlier -D"));
}
