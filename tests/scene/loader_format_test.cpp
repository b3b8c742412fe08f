// What each key of the scene format means (docs/scene-format.md), checked against hand-computed
// values: defaults, transform order, the matrix layout, merging onto a generator, -D overrides.
#include <catch2/catch.hpp>

#include "scene/scene_info.h"
#include "scene/scene_loader.h"

using namespace shadowref;
using Catch::Matchers::Contains;

namespace {

Scene load(const std::string& yaml, std::vector<std::string> overrides = {}) {
  LoadOptions o;
  o.overrides = std::move(overrides);
  return loadSceneFromString(yaml, "t.yaml", o);
}

const std::string kBox = "meshes:\n  box: {box: {}}\n";

// The world position of object-space point p under the first root's local matrix.
glm::dvec3 place(const Scene& s, glm::dvec3 p) { return glm::dvec3(s.roots.at(0).local * glm::dvec4(p, 1.0)); }

void checkNear(glm::dvec3 a, glm::dvec3 b) {
  INFO("(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", " << b.z << ")");
  CHECK(glm::length(a - b) < 1e-12);
}

}  // namespace

TEST_CASE("omitted keys keep the defaults of scene.h", "[loader]") {
  const Scene s = load("camera: {}\n");
  const Scene d;
  CHECK(s.width == d.width);
  CHECK(s.height == d.height);
  CHECK(s.depthFormat == DepthFormat::Float32);
  CHECK(s.camera.eye == d.camera.eye);
  CHECK(s.camera.fovYDegrees == 60.0);
  CHECK(s.camera.farPlane == kInfinity);
  CHECK(s.shadow.method == "none");
  CHECK(s.shadow.compareFail == 0.4);
  REQUIRE(s.materials.size() == 1);
  CHECK(s.materials[0].name == "default");
  CHECK(s.lights.empty());
}

TEST_CASE("every section's keys set the matching scene fields", "[loader]") {
  const Scene s = load(
      "image: {width: 320, height: 200, depth: unorm24}\n"
      "camera: {eye: [1, 2, 3], target: [0, 1, 0], up: [0, 0, 1], fov: 35, near: 0.25, far: 80}\n"
      "ambient: [0.1, 0.2, 0.3]\n"
      "background: 0.5\n"
      "lights:\n"
      "  - {name: s, type: spot, position: [0, 4, 0], direction: [0, -1, 0], color: [1, 0.5, 0.25], range: 12,\n"
      "     spot_cutoff: 30, spot_exponent: 4, attenuation: [1, 0.1, 0.01], soft: {shape: sphere14, spacing: 0.3}}\n"
      "  - {type: directional, direction: [1, -1, 0]}\n"
      "materials:\n"
      "  m: {ambient: 0.1, diffuse: [0.9, 0.8, 0.7], specular: 1, shininess: 64, shading: gouraud, blinn: true}\n"
      "shadow: {method: tsm, silhouette: lengyel, two_sided: false, wrap: false, darken_composite: true,\n"
      "         map_size: 512, offset_factor: 2, offset_units: 8, bias: 0.001, back_faces_only: true, pcf: 3,\n"
      "         compare_fail: 0.5, focus_region: 0.3}\n");
  CHECK(s.width == 320);
  CHECK(s.height == 200);
  CHECK(s.depthFormat == DepthFormat::Unorm24);
  CHECK(s.camera.eye == glm::dvec3(1, 2, 3));
  CHECK(s.camera.up == glm::dvec3(0, 0, 1));
  CHECK(s.camera.fovYDegrees == 35.0);
  CHECK(s.camera.nearPlane == 0.25);
  CHECK(s.camera.farPlane == 80.0);
  CHECK(s.ambient == glm::dvec3(0.1, 0.2, 0.3));
  CHECK(s.background == glm::dvec3(0.5));
  REQUIRE(s.lights.size() == 2);
  const Light& l = s.lights[0];
  CHECK(l.name == "s");
  CHECK(l.type == LightType::Spot);
  CHECK(l.color == glm::dvec3(1, 0.5, 0.25));
  CHECK(l.range == 12.0);
  CHECK(l.spotCutoffDegrees == 30.0);
  CHECK(l.spotExponent == 4.0);
  CHECK(l.attenuation == glm::dvec3(1, 0.1, 0.01));
  CHECK(l.soft == SoftShape::Sphere14);
  CHECK(l.softSpacing == 0.3);
  CHECK(s.lights[1].name == "light1");  // unnamed: "light" + its index
  CHECK(s.lights[1].type == LightType::Directional);
  REQUIRE(s.materials.size() == 2);
  const Material& m = s.materials[1];
  CHECK(m.name == "m");
  CHECK(m.ambient == glm::dvec3(0.1));
  CHECK(m.specular == glm::dvec3(1.0));
  CHECK(m.shininess == 64.0);
  CHECK(m.shading == ShadingModel::Gouraud);
  CHECK(m.blinn);
  const ShadowSettings& sh = s.shadow;
  CHECK(sh.method == "tsm");
  CHECK(sh.silhouette == SilhouetteAlgorithm::Lengyel);
  CHECK(!sh.twoSidedStencil);
  CHECK(!sh.wrapOps);
  CHECK(sh.darkenComposite);
  CHECK(sh.mapSize == 512);
  CHECK(sh.offsetFactor == 2.0);
  CHECK(sh.offsetUnits == 8.0);
  CHECK(sh.constantBias == 0.001);
  CHECK(sh.backFacesOnly);
  CHECK(sh.pcf == 3);
  CHECK(sh.compareFail == 0.5);
  CHECK(sh.focusRegion == 0.3);
}

TEST_CASE("a node scales first, then rotates, then translates", "[loader]") {
  // (1, 0, 0) scaled by 2 -> (2, 0, 0); 90 degrees about +y -> (0, 0, -2); moved by (10, 0, 0).
  const Scene s = load(kBox + "nodes:\n  - {mesh: box, translate: [10, 0, 0], rotate: {axis: [0, 1, 0], angle: 90}, scale: 2}\n");
  checkNear(place(s, {1, 0, 0}), {10, 0, -2});
}

TEST_CASE("euler angles rotate about X first, then Y, then Z", "[loader]") {
  // (0, 1, 0): X by 90 -> (0, 0, 1); Y by 90 -> (1, 0, 0); Z by 90 -> (0, 1, 0).
  const Scene s = load(kBox + "nodes:\n  - {mesh: box, rotate: {euler: [90, 90, 90]}}\n");
  checkNear(place(s, {0, 1, 0}), {0, 1, 0});
  // (0, 0, 1): X -> (0, -1, 0); Y leaves it; Z by 90 -> (1, 0, 0).
  checkNear(place(s, {0, 0, 1}), {1, 0, 0});
}

TEST_CASE("a matrix is written row by row: the translation is the last column", "[loader]") {
  const Scene s = load(kBox + "nodes:\n  - {mesh: box, matrix: [0, -1, 0, 5,  1, 0, 0, 6,  0, 0, 1, 7,  0, 0, 0, 1]}\n");
  // Row 1 (0, -1, 0, 5) gives x' = -y + 5; row 2 gives y' = x + 6; row 3 z' = z + 7.
  checkNear(place(s, {1, 2, 3}), {3, 7, 10});
  const Scene rows = load(kBox + "nodes:\n  - {mesh: box, matrix: [[0, -1, 0, 5], [1, 0, 0, 6], [0, 0, 1, 7], [0, 0, 0, 1]]}\n");
  CHECK(rows.roots[0].local == s.roots[0].local);
}

TEST_CASE("children compose with their parent and are named after their mesh when unnamed", "[loader]") {
  const Scene s = load(kBox + "nodes:\n  - name: group\n    translate: [1, 0, 0]\n    children:\n"
                              "      - {mesh: box, translate: [0, 2, 0], cast_shadows: false}\n");
  const std::vector<Instance> inst = s.instances();
  REQUIRE(inst.size() == 1);
  CHECK(inst[0].path == "group/box");
  checkNear(glm::dvec3(inst[0].world * glm::dvec4(0, 0, 0, 1)), {1, 2, 0});
  CHECK(inst[0].shadowMesh == nullptr);
}

TEST_CASE("a shadow proxy replaces the mesh in the shadow pass only", "[loader]") {
  const Scene s = load("meshes:\n  ball: {sphere: {}}\n  lod: {sphere: {slices: 6, stacks: 3}}\n"
                       "nodes:\n  - {mesh: ball, shadow_proxy: lod}\n");
  const std::vector<Instance> inst = s.instances();
  REQUIRE(inst.size() == 1);
  CHECK(inst[0].mesh->name == "ball");
  REQUIRE(inst[0].shadowMesh != nullptr);
  CHECK(inst[0].shadowMesh->name == "lod");
  CHECK(inst[0].shadowMesh->triangles.size() == 6 * 2 * (3 - 1));  // two polar fans + one band of quads
}

TEST_CASE("the file's keys change what the generator made, new names add", "[loader]") {
  const Scene base = load("generator: room\n");
  const Scene s = load("generator: {type: room}\n"
                       "camera: {fov: 40}\n"
                       "lights:\n  - {name: ceiling, soft: {shape: square_y}}\n  - {name: extra, position: [1, 1, 1]}\n"
                       "materials:\n  shiny: {specular: 1}\n");
  REQUIRE(base.lights.size() == 1);
  REQUIRE(s.lights.size() == 2);
  CHECK(s.lights[0].name == "ceiling");
  CHECK(s.lights[0].soft == SoftShape::SquareY);
  CHECK(s.lights[0].position == base.lights[0].position);  // only the written key changed
  CHECK(s.lights[1].name == "extra");
  CHECK(s.camera.fovYDegrees == 40.0);
  CHECK(s.camera.eye == base.camera.eye);
  CHECK(s.materials.size() == base.materials.size() + 1);
  CHECK(s.instances().size() == base.instances().size());
}

TEST_CASE("overrides given with -D apply after the file, in command-line order", "[loader]") {
  const std::string file = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/scenes/good_overrides.yaml";
  LoadOptions o;
  o.overrides = {"camera.near=0.001", "lights.0.range=5", "lights.fill.soft.shape=area16", "shadow.method=zfail",
                 "materials.paint.diffuse=[0.1, 0.2, 0.3]", "ambient=0.05", "image.depth=unorm24",
                 "shadow.method=zpass", "camera.far=infinite"};
  const Scene s = loadScene(file, o);
  CHECK(s.camera.nearPlane == 0.001);
  CHECK(s.lights[0].range == 5.0);
  CHECK(s.lights[1].soft == SoftShape::AreaEdge16);
  CHECK(s.shadow.method == "zpass");  // the later -D wins
  CHECK(s.materials[1].diffuse == glm::dvec3(0.1, 0.2, 0.3));
  CHECK(s.ambient == glm::dvec3(0.05));
  CHECK(s.depthFormat == DepthFormat::Unorm24);
  CHECK(s.camera.farPlane == kInfinity);
  CHECK(s.camera.eye == glm::dvec3(0, 2, 6));  // untouched
}

TEST_CASE("an override of generator.* with -D changes the generator's options before it runs", "[loader]") {
  const Scene eight = load("generator: {type: city, houses: 64}\n", {"generator.houses=8"});
  const Scene sixteen = load("generator: city\n", {"generator.houses=16"});
  CHECK(eight.instances().size() < sixteen.instances().size());
  const Scene again = load("generator: {type: city, houses: 8}\n");
  CHECK(again.instances().size() == eight.instances().size());
  const Scene framed = load("generator: {type: city, houses: 8}\n", {"generator.framed_houses=100"});
  const Scene hundred = load("generator: city\n", {"generator.houses=100"});
  CHECK(framed.instances().size() == eight.instances().size());
  CHECK(framed.camera.eye == hundred.camera.eye);
  CHECK(framed.camera.eye != eight.camera.eye);
}

TEST_CASE("describeScene lists nodes, meshes with topology, lights, bounds and the method", "[loader]") {
  const Scene s = load(kBox + "lights: [{name: bulb, position: [0, 3, 0]}]\n"
                              "nodes:\n  - {name: crate, mesh: box, translate: [2, 0.5, 0]}\n"
                              "shadow: {method: zfail}\n");
  const std::string text = describeScene(s);
  CHECK_THAT(text, Contains("box: 12 triangles, 8 welded vertices, 18 edges, closed (0 open, 0 non-manifold edges), "
                            "encloses volume 1, bounds"));
  CHECK_THAT(text, Contains("crate  mesh box, material default, world bounds (1.5, 0, -0.5) .. (2.5, 1, 0.5)"));
  CHECK_THAT(text, Contains("bulb: point at (0, 3, 0)"));
  // The technique's settings are described by the technique (src/shadow), passed in.
  CHECK_THAT(text, Contains("\nshadow: zfail\n"));
  CHECK_THAT(describeScene(s, "silhouette kuhn"), Contains("\nshadow: zfail, silhouette kuhn\n"));
  CHECK_THAT(text, Contains("total: 1 instances, 12 triangles drawn"));
}

TEST_CASE("a glTF mesh is read from its path and welded", "[loader]") {
  const std::string file = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/meshes/tetra.gltf";
  const Scene s = load("meshes:\n  t: {gltf: '" + file + "'}\nnodes:\n  - {mesh: t}\n");
  REQUIRE(s.meshes.size() == 1);
  CHECK(s.meshes[0]->name == "t");
  CHECK(s.meshes[0]->triangles.size() == 4);  // a tetrahedron
  CHECK(s.meshes[0]->weldedPositions.size() == 4);
  CHECK(s.meshes[0]->topology == Topology::Closed);
}

TEST_CASE("the world bounds of instances are their boxes together, and an instance without bounds adds nothing", "[loader]") {
  std::vector<Instance> instances(3);
  instances[0].worldBounds.add({-1.0, 0.0, 2.0});
  instances[0].worldBounds.add({1.0, 3.0, 4.0});
  instances[2].worldBounds.add({0.5, -2.0, -5.0});  // a single point
  // instances[1] has none (empty)
  const Aabb box = worldBounds(instances);
  CHECK(box.min == glm::dvec3(-1.0, -2.0, -5.0));
  CHECK(box.max == glm::dvec3(1.0, 3.0, 4.0));
  CHECK(worldBounds({}).empty());
}
