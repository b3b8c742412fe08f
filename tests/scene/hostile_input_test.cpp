// Hostile input to the scene loader: inputs built to exhaust the stack (a -D key of thousands of
// names, YAML nested thousands deep), memory (aliases that repeat a large mesh) or to slip a
// non-finite number past the checks (tiny or huge vectors, overflowing transforms). Each is
// rejected with "file:line:column: message" at the place that is wrong — the expected column is
// found in the input text by the test itself — or, where the input has a well-defined meaning
// ([1e-320, 0, 0] is the x axis), loads with that meaning.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/resource_limits.h"
#include "scene/scene_loader.h"
#include "support/errors.h"

using namespace shadowref;
using shadowref::testing::yamlErrorOf;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

LoadOptions overrides(std::vector<std::string> list) { return LoadOptions{std::move(list)}; }

// "t.yaml:LINE:COLUMN" of the first occurrence of `needle` at or after `from` in `text`, counted
// here from the text itself.
std::string at(const std::string& text, const std::string& needle, size_t from = 0) {
  const size_t pos = text.find(needle, from);
  REQUIRE(pos != std::string::npos);
  const size_t lineStart = text.rfind('\n', pos) == std::string::npos ? 0 : text.rfind('\n', pos) + 1;
  size_t line = 1;
  for (size_t i = 0; i < pos; ++i) line += text[i] == '\n';
  return "t.yaml:" + std::to_string(line) + ":" + std::to_string(pos - lineStart + 1);
}

const std::string kBoxMesh = "meshes:\n  box: {box: {}}\n";  // 12 triangles, 24 vertices (4 per face)

}  // namespace

TEST_CASE("a -D key of thousands of names is rejected at its 65th name, without recursion", "[loader][hostile]") {
  // 20 000 names, 40 KB: one stack frame per name overflowed the stack.
  std::string key = "camera";
  for (int i = 0; i < 20000; ++i) key += ".a";
  // Name k (from 0) starts at 7 + 2 (k - 1) for k >= 1; the 65th is k = 64: column 7 + 126 + 1.
  CHECK_THAT(yamlErrorOf(kBoxMesh, overrides({key + "=1"})),
             StartsWith("<command line>:1:134: -D key: more than 64 names separated by '.'"));
  // generator.* keys are merged into the generator section before it runs: the same limit.
  std::string generatorKey = "generator";
  for (int i = 0; i < 20000; ++i) generatorKey += ".a";
  CHECK_THAT(yamlErrorOf(kBoxMesh, overrides({"camera.near=0.5", generatorKey + "=1"})),
             StartsWith("<command line>:2:137: -D key: more than 64 names"));
  // 64 names are not rejected for their number (but camera takes one name, found at the third).
  std::string sixtyFour = "camera";
  for (int i = 1; i < 64; ++i) sixtyFour += ".a";
  CHECK_THAT(yamlErrorOf(kBoxMesh, overrides({sixtyFour + "=1"})), StartsWith("<command line>:1:10: -D camera.a.a"));
}

TEST_CASE("YAML nested deeper than 64 levels is an error at the 65th level, before yaml-cpp recurses", "[loader][hostile]") {
  // Flow style, 3000 deep: yaml-cpp's own guard said "YAML syntax error: bad file" at 1:1.
  const std::string flow = "nodes: " + std::string(3000, '[') + std::string(3000, ']') + "\n";
  // The root map is level 1; the k-th '[' is level k + 1, so level 65 is the 64th '['.
  CHECK_THAT(yamlErrorOf(flow), StartsWith("t.yaml:1:" + std::to_string(7 + 64) +
                                       ": lists and maps nested more than 64 levels deep"));
  // Block style, 600 deep: level d is the map whose key stands on line d, indented 2 (d - 1).
  std::string block;
  for (int d = 1; d <= 600; ++d) block += std::string(2 * (d - 1), ' ') + "a:\n";
  CHECK_THAT(yamlErrorOf(block), StartsWith("t.yaml:65:129: lists and maps nested more than 64 levels deep"));
  // 64 levels are parsed (and then checked as a scene: the key is unknown).
  CHECK_THAT(yamlErrorOf("nodes: " + std::string(63, '[') + std::string(63, ']') + "\n"), !Contains("nested"));
  // A -D value: its first '[' is level 1, at the value's first column (12).
  const std::string value = std::string(100, '[') + std::string(100, ']');
  CHECK_THAT(yamlErrorOf(kBoxMesh, overrides({"camera.eye=" + value})),
             StartsWith("<command line>:1:" + std::to_string(12 + 64) + ": lists and maps nested more than 64"));
}

TEST_CASE("an error in a -D value spanning lines stays on the option's line, at its column", "[loader][hostile]") {
  // "camera.near=\nabc": 'a' is character 14 of the argument.
  CHECK_THAT(yamlErrorOf(kBoxMesh, overrides({"camera.near=\nabc"})),
             StartsWith("<command line>:1:14: camera.near: expected a number, got 'abc'"));
  // The second option; 'z' is character 18 of "shadow.method=\n  zfial". The loader keeps any
  // technique name and where it stands; the registry reports it there
  // (tests/shadow/technique_registry_test.cpp).
  const Scene s = loadSceneFromString(kBoxMesh, "t.yaml", overrides({"camera.near=0.5", "shadow.method=\n  zfial"}));
  CHECK(s.shadow.method == "zfial");
  CHECK(formatLocation(s.shadow.methodAt) == "<command line>:2:18");
}

TEST_CASE("the resource budget is checked before instancing, at the first node that does not fit", "[loader][hostile]") {
  const std::string three = kBoxMesh + "nodes:\n  - {mesh: box}\n  - {mesh: box}\n  - {mesh: box}\n";
  const std::string thirdNode = at(three, "{mesh", three.find("{mesh", three.find("{mesh") + 1) + 1);
  CHECK(yamlErrorOf(three) == "(no error)");
  CHECK_THAT(yamlErrorOf(three, overrides({"limits.max_instances=2"})),
             StartsWith(thirdNode + ": nodes.2: the scene needs more than 2 instances (the limit limits.max_instances; "
                                    "raise it with 'limits: {max_instances: N}' in the scene or -D limits.max_instances=N)"));
  CHECK(yamlErrorOf(three, overrides({"limits.max_instances=3"})) == "(no error)");
  // 3 x 12 = 36 triangles, 3 x 24 = 72 vertices.
  const std::string tris = "limits: {max_triangles: 35}\n" + three;
  CHECK_THAT(yamlErrorOf(tris), StartsWith(at(tris, "{mesh", tris.find("{mesh", tris.find("{mesh") + 1) + 1) +
                                       ": nodes.2: the scene needs more than 35 triangles after instancing"));
  CHECK(yamlErrorOf("limits: {max_triangles: 36}\n" + three) == "(no error)");
  CHECK_THAT(yamlErrorOf(three, overrides({"limits.max_vertices=71"})),
             StartsWith(thirdNode + ": nodes.2: the scene needs more than 71 vertices after instancing"));
  CHECK(yamlErrorOf(three, overrides({"limits.max_vertices=72"})) == "(no error)");
  // Children count as instances, each at its own node; a shadow proxy adds its triangles.
  const std::string nested = kBoxMesh + "nodes:\n  - {name: g, children: [{mesh: box}, {mesh: box}]}\n";
  CHECK_THAT(yamlErrorOf(nested, overrides({"limits.max_instances=1"})),
             StartsWith(at(nested, "{mesh", nested.find("{mesh") + 1) + ": nodes.0.children.1: the scene needs more"));
  const std::string proxy = kBoxMesh + "nodes:\n  - {mesh: box, shadow_proxy: box}\n";
  CHECK_THAT(yamlErrorOf(proxy, overrides({"limits.max_triangles=23"})), Contains("more than 23 triangles"));
  CHECK(yamlErrorOf(proxy, overrides({"limits.max_triangles=24"})) == "(no error)");
  // Limits are whole numbers from 1 to 2^40.
  CHECK_THAT(yamlErrorOf(three, overrides({"limits.max_instances=0"})),
             StartsWith("<command line>:1:22: limits.max_instances: expected a whole number from 1 to 2^40"));
  CHECK_THAT(yamlErrorOf("limits: {max_triangles: 2.5}\n"), StartsWith("t.yaml:1:25: limits.max_triangles: expected a whole number"));
  CHECK_THAT(yamlErrorOf("limits: {max_trinagles: 5}\n"), Contains("did you mean 'max_triangles'?"));
}

TEST_CASE("YAML aliases that repeat a mesh 111 111 times are rejected by the budget", "[loader][hostile]") {
  const std::string file = std::string(SHADOWREF_SOURCE_DIR) + "/tests/data/hostile/alias_bomb_instances.yaml";
  std::string e;
  try {
    loadScene(file);
  } catch (const SceneError& error) {
    e = error.what();
    CHECK(error.where().line > 0);
  }
  CHECK_THAT(e, StartsWith(file + ":"));
  // 32 514 vertices and 65 024 triangles an instance: the vertices pass 2^23 first, at the 258th.
  CHECK_THAT(e, Contains("more than 8388608 vertices after instancing (the limit limits.max_vertices;"));
}

TEST_CASE("the budget's sums cannot wrap around", "[loader][hostile]") {
  const std::uint64_t all = ~std::uint64_t(0), big = std::uint64_t(1) << 40;
  ResourceBudget budget(ResourceLimits{.maxInstances = all, .maxTriangles = all, .maxVertices = all});
  CHECK(budget.add(1, 1).empty());
  // 2^30 copies of 2^40 triangles or vertices is 2^70, and 1 + (2^64 - 1) instances is 2^64:
  // rejected, not wrapped around to a small number.
  CHECK_THAT(budget.add(big, 1, std::uint64_t(1) << 30), Contains("(the limit limits.max_triangles"));
  CHECK_THAT(budget.add(1, big, std::uint64_t(1) << 30), Contains("(the limit limits.max_vertices"));
  CHECK_THAT(budget.add(1, 1, all), Contains("(the limit limits.max_instances"));
  CHECK(budget.instances() == 1);
  CHECK(budget.triangles() == 1);
  CHECK(imagePixels(8192, 8192) == std::optional<std::uint64_t>(1u << 26));
  CHECK(!imagePixels(8192, 8193));
  CHECK(!imagePixels(16385, 1));
  CHECK(!imagePixels(0, 5));
}

TEST_CASE("a direction or axis with tiny components is normalised exactly, a huge one rejected", "[loader][hostile]") {
  // [1e-320, 0, 0] passed the zero test and normalised to NaN (its squared length underflows).
  Scene s = loadSceneFromString("lights:\n  - {type: directional, direction: [1e-320, 0, 0]}\n", "t.yaml");
  const glm::dvec4 h = s.lights[0].homogeneous();
  CHECK(h.x == Approx(-1.0).epsilon(1e-15));
  CHECK((h.y == 0.0 && h.z == 0.0 && h.w == 0.0));
  s = loadSceneFromString("lights:\n  - {type: spot, direction: [0, -4.9e-324, 4.9e-324]}\n", "t.yaml");
  const glm::dvec3 d = glm::normalize(s.lights[0].direction);
  CHECK(d.x == 0.0);
  CHECK(d.y == Approx(-std::sqrt(0.5)).epsilon(1e-15));
  CHECK(d.z == Approx(std::sqrt(0.5)).epsilon(1e-15));
  // A direction in the usual range is kept as written.
  s = loadSceneFromString("lights:\n  - {type: directional, direction: [-0.4, -1, -0.3]}\n", "t.yaml");
  CHECK(s.lights[0].direction == glm::dvec3(-0.4, -1.0, -0.3));

  const std::string huge = "lights:\n  - {type: directional, direction: [-1e308, 0, 0]}\n";
  CHECK_THAT(yamlErrorOf(huge), StartsWith(at(huge, "-1e308") + ": lights.0.direction.0: '-1e308' is too large; "
                                                            "a scene's numbers lie within +-1e15"));
  // A rotation about [1e-320, 0, 0] by 90 degrees turns y into z (the node vanished before).
  s = loadSceneFromString(kBoxMesh + "nodes:\n  - {mesh: box, rotate: {axis: [1e-320, 0, 0], angle: 90}}\n", "t.yaml");
  const glm::dvec4 y = s.roots[0].local * glm::dvec4(0, 1, 0, 0);
  CHECK(y.x == 0.0);
  CHECK(std::fabs(y.y) < 1e-15);
  CHECK(y.z == Approx(1.0).epsilon(1e-15));
  CHECK(s.instances().size() == 1);
  const std::string zeroAxis = kBoxMesh + "nodes:\n  - {mesh: box, rotate: {axis: [0, 0, 0], angle: 90}}\n";
  CHECK_THAT(yamlErrorOf(zeroAxis), StartsWith(at(zeroAxis, "[0, 0, 0]") + ": nodes.0.rotate.axis: the rotation axis must not be the zero vector"));
  // The camera's up vector too.
  CHECK(yamlErrorOf(kBoxMesh + "camera: {up: [0, 1e-320, 0]}\n") == "(no error)");
}

TEST_CASE("numbers beyond 1e15 are rejected where written: light positions, spacings, the camera", "[loader][hostile]") {
  const std::string position = "lights:\n  - {position: [1.7e308, 0, 0]}\n";
  CHECK_THAT(yamlErrorOf(position), StartsWith(at(position, "1.7e308") + ": lights.0.position.0: '1.7e308' is too large"));
  const std::string spacing = "lights:\n  - {soft: {shape: sphere14, spacing: 1e300}}\n";
  CHECK_THAT(yamlErrorOf(spacing), StartsWith(at(spacing, "1e300") + ": lights.0.soft.spacing: '1e300' is too large"));
  const std::string eye = "camera: {eye: [1e308, 0, 0]}\n";
  CHECK_THAT(yamlErrorOf(eye), StartsWith(at(eye, "1e308") + ": camera.eye.0: '1e308' is too large"));
  CHECK_THAT(yamlErrorOf(kBoxMesh, overrides({"lights.0.position=[0, 2e15, 0]"})), !Contains("too large"));  // no light 0
  CHECK_THAT(yamlErrorOf("lights: [{}]\n", overrides({"lights.0.position=[0, 2e15, 0]"})),
             StartsWith("<command line>:1:23: lights.0.position.1: '2e15' is too large"));
  // The bound itself is allowed.
  CHECK(yamlErrorOf("lights:\n  - {position: [1e15, -1e15, 0]}\n") == "(no error)");
}

TEST_CASE("eye and target too close together are reported as such, not as a parallel up vector", "[loader][hostile]") {
  const std::string tiny = "camera: {eye: [0, 0, 0], target: [1e-300, 0, 0]}\n";
  CHECK_THAT(yamlErrorOf(tiny), StartsWith(at(tiny, "[1e-300") + ": camera: eye and target are too close together (1e-300 apart)"));
  // 1e-6 apart at 1e14 from the origin: below the coordinates' rounding (1e14 * 1e-9).
  const std::string far = "camera: {eye: [1e14, 0, 0], target: [1e14, 1e-6, 0]}\n";
  CHECK_THAT(yamlErrorOf(far), StartsWith(at(far, "[1e14, 1e-6") + ": camera: eye and target are too close together (1e-06 apart)"));
  // A parallel up vector is still that.
  const std::string parallel = "camera: {eye: [0, 5, 0], target: [0, 0, 0]}\n";
  CHECK_THAT(yamlErrorOf(parallel), StartsWith("t.yaml:1:1: camera.up: the up vector is parallel to the view direction"));
  // A field of view so small that the projection is infinite.
  const std::string fov = "camera: {fov: 1e-320}\n";
  CHECK_THAT(yamlErrorOf(fov), StartsWith(at(fov, "1e-320") + ": camera: the projection matrix is not finite"));
}

TEST_CASE("node world transforms that overflow or underflow are errors at the node", "[loader][hostile]") {
  // 1e12 at each of three levels: 1e36 at the third, beyond 1e30.
  const std::string up = kBoxMesh +
                         "nodes:\n  - {name: a, scale: 1e12, children: [{name: b, scale: 1e12, children: [{mesh: box, scale: 1e12}]}]}\n";
  CHECK_THAT(yamlErrorOf(up), StartsWith(at(up, "{mesh") + ": nodes.0.children.0.children.0: the world transform has entries beyond +-1e30"));
  // 1e-100 twice: the determinant 1e-600 underflows to 0.
  const std::string down = kBoxMesh + "nodes:\n  - {name: a, scale: 1e-100, children: [{mesh: box, scale: 1e-100}]}\n";
  CHECK_THAT(yamlErrorOf(down), StartsWith(at(down, "{mesh") + ": nodes.0.children.0: the world transform is singular"));
  CHECK(yamlErrorOf(kBoxMesh + "nodes:\n  - {name: a, scale: 1e-100, children: [{mesh: box}]}\n") == "(no error)");
  // A tiny constant attenuation whose inverse is infinite.
  const std::string attenuation = "lights:\n  - {attenuation: [1e-320, 0, 0]}\n";
  CHECK_THAT(yamlErrorOf(attenuation), StartsWith(at(attenuation, "[1e-320") + ": lights.0.attenuation: the constant term"));
}

TEST_CASE("many materials and nodes are looked up by name correctly", "[loader][hostile]") {
  // 20 000 materials and a node for each: every node gets its own material (index i + 1, after
  // the default). The lookups are hashed, so this is linear in the scene's size.
  const int n = 20000;
  std::string yaml = kBoxMesh + "materials:\n";
  for (int i = 0; i < n; ++i) yaml += "  m" + std::to_string(i) + ": {diffuse: 0.5}\n";
  yaml += "nodes:\n";
  for (int i = 0; i < n; ++i) yaml += "  - {mesh: box, material: m" + std::to_string(i) + "}\n";
  const Scene s = loadSceneFromString(yaml, "t.yaml");
  REQUIRE(s.roots.size() == size_t(n));
  bool allRight = true;
  for (int i = 0; i < n; ++i) allRight = allRight && s.materials[size_t(s.roots[size_t(i)].material)].name == "m" + std::to_string(i);
  CHECK(allRight);
  // An unknown name still gets its suggestion.
  CHECK_THAT(yamlErrorOf(kBoxMesh + "materials: {wall: {}}\nnodes:\n  - {mesh: box, material: wal}\n"),
             Contains("did you mean 'wall'?"));
  // Lights named twice in the file: the second entry changes the first light.
  const Scene l = loadSceneFromString("lights:\n  - {name: a, range: 2}\n  - {name: a, range: 3}\n", "t.yaml");
  REQUIRE(l.lights.size() == 1);
  CHECK(l.lights[0].range == 3.0);
}

TEST_CASE("a long string repeated by aliases is rejected before it is copied", "[loader][hostile]") {
  // 1 MB of text, 100 copies through aliases: 100 MB after expansion, more than 2^26 bytes.
  const std::string text(1 << 20, 'x');
  std::string yaml = "materials:\n  m: {name: &t " + text + "}\nnodes: [";
  for (int i = 0; i < 100; ++i) yaml += std::string(i ? ", " : "") + "*t";
  yaml += "]\n";
  const std::string e = yamlErrorOf(yaml);
  // At the copied value, which yaml-cpp locates at its anchor: line 2, the '&' at column 13.
  CHECK_THAT(e, StartsWith("t.yaml:2:13: "));
  CHECK_THAT(e, Contains("the document's text is more than 67108864 bytes after aliases are expanded"));
}

TEST_CASE("an unknown name among many long names gets its error without an edit-distance hang", "[loader][hostile]") {
  // 2000 materials with names of 200 characters and a node naming an unknown one of 200: the
  // suggestion search would be 2000 * 200 * 200 = 8e7 steps; it stops after its work budget and
  // still finds a name close enough when one comes early.
  std::string yaml = kBoxMesh + "materials:\n";
  const std::string stem(199, 'n');
  for (int i = 0; i < 2000; ++i) yaml += "  " + stem + std::to_string(i % 10) + std::to_string(i) + ": {}\n";
  yaml += "nodes:\n  - {mesh: box, material: " + stem + "00x}\n";
  const std::string e = yamlErrorOf(yaml);
  CHECK_THAT(e, Contains("no material named"));
  CHECK_THAT(e, Contains("did you mean '" + stem + "00'?"));
  // A word longer than 256 characters gets no suggestion at all.
  CHECK_THAT(yamlErrorOf(kBoxMesh + "nodes:\n  - {mesh: box, material: " + std::string(300, 'q') + "}\n"),
             !Contains("did you mean"));
}
